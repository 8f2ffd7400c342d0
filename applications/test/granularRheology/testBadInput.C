/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Description
    Bad input: a FatalIOError naming the dictionary, the keyword and the
    value, for every law and for granularProperties.

\*---------------------------------------------------------------------------*/

#include "granularRheologyTest.H"
#include "BarkerGray.H"
#include "grainPairModels.H"
#include "segregationVelocity.H"
#include "diffusivity.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
namespace granularRheologyTest
{

void testBadInput()
{
    auto rheology = [](const std::string& text)
    {
        return [text]{ granularRheology r(parse(text)); };
    };

    expectError("bad input: d <= 0",
        rheology(properties(0, 2e-3)), {"'d'", "0"});
    expectError("bad input: rhoStar <= 0",
        rheology("rhoStar -1; Phi 0.6; etaMax 1; grains { a { d 1e-3; " + table1Jop + " } }"),
        {"'rhoStar'", "-1"});
    expectError("bad input: Phi > 1",
        rheology("rhoStar 2500; Phi 1.5; etaMax 1; grains { a { d 1e-3; " + table1Jop + " } }"),
        {"'Phi'", "1.5"});
    expectError("bad input: etaMax <= 0",
        rheology("rhoStar 2500; Phi 0.6; etaMax 0; grains { a { d 1e-3; " + table1Jop + " } }"),
        {"'etaMax'"});
    expectError("bad input: pMin <= 0",
        rheology(properties(1e-3, 2e-3, table1Jop, "pMin -1;")), {"'pMin'", "-1"});
    expectError("bad input: missing etaMax",
        rheology("rhoStar 2500; Phi 0.6; grains { a { d 1e-3; " + table1Jop + " } }"),
        {"etaMax"});
    expectError("bad input: mu_s > mu_d (Jop)",
        rheology(properties(1e-3, 2e-3,
            "frictionLaw Jop; JopCoeffs { mus 0.6; mud 0.5; I0 0.3; }")),
        {"'mus'", "0.6"});
    expectError("bad input: mu_s > mu_d (BarkerGray)",
        rheology(properties(1e-3, 2e-3,
            "frictionLaw BarkerGray; BarkerGrayCoeffs { mus 0.6; mud 0.5;"
            " muInf 0.05; I0 0.069; alpha 1.9; I1 0.004; }")),
        {"'mus'", "0.6"});
    expectError("bad input: I0 <= 0",
        rheology(properties(1e-3, 2e-3,
            "frictionLaw Jop; JopCoeffs { mus 0.3; mud 0.5; I0 0; }")),
        {"'I0'"});
    expectError("bad input: alpha <= 0",
        rheology(properties(1e-3, 2e-3,
            "frictionLaw BarkerGray; BarkerGrayCoeffs { mus 0.342; mud 0.557;"
            " muInf 0.05; I0 0.069; alpha -1.9; I1 0.004; }")),
        {"'alpha'", "-1.9"});
    expectError("bad input: unknown friction law lists the valid ones",
        rheology(properties(1e-3, 2e-3, "frictionLaw Coulomb;")),
        {"Coulomb", "BarkerGray", "Jop", "constant"});
    expectError("bad input: weightedParameters with two law types",
        rheology("rhoStar 2500; Phi 0.6; etaMax 1; mixtureRule weightedParameters;"
            " grains { a { d 1e-3; " + table1Jop + " } b { d 2e-3; " + table1BG + " } }"),
        {"weightedParameters", "BarkerGray"});
    expectError("bad input: unknown mixture rule",
        rheology(properties(1e-3, 2e-3, table1Jop, "mixtureRule average;")),
        {"average"});

    const dictionary props(parse(properties(1e-3, 2e-3)));
    const granularRheology rh(props);
    auto pairs = [&rh](const std::string& text)
    {
        return [text, &rh]
        {
            grainPairModels<segregationVelocity> p(parse(text), "segregation", rh);
        };
    };
    expectError("bad input: pair names an unknown phase",
        pairs("segregation { x { phases (small air); model constant; f 1; } }"),
        {"air", "phases"});
    expectError("bad input: pair given twice",
        pairs("segregation { x { phases (small large); model constant; f 1; }"
              " y { phases (large small); model constant; f 2; } }"),
        {"twice"});
    expectError("bad input: missing pair",
        pairs("segregation { }"), {"small", "large"});
    expectError("bad input: phase paired with itself",
        pairs("segregation { x { phases (small small); model constant; f 1; } }"),
        {"itself"});
    expectError("bad input: unknown segregation model lists the valid ones",
        pairs("segregation { x { phases (small large); model GrayThornton; } }"),
        {"GrayThornton", "Trewhela", "constant"});
    expectError("bad input: negative segregation velocity",
        pairs("segregation { x { phases (small large); model constant; f -1; } }"),
        {"'f'", "-1"});
    expectError("bad input: negative Trewhela B",
        pairs("segregation { x { phases (small large); model Trewhela; TrewhelaCoeffs { B -0.3; } } }"),
        {"'B'", "-0.3"});
    expectError("bad input: unknown diffusion model lists the valid ones",
        [&rh]
        {
            grainPairModels<diffusivity> p
            (
                parse("diffusion { x { phases (small large); model Fick; } }"),
                "diffusion", rh
            );
        },
        {"Fick", "UtterBehringer", "constant"});

    // One grain phase (monodisperse): no pair, so the pair dictionaries
    // may be absent or empty, and an entry is refused
    const granularRheology mono
    (
        parse("rhoStar 2500; Phi 0.6; etaMax 1; grains { a { d 1e-3; "
            + table1Jop + " } }")
    );
    check("one grain phase: no segregation sub-dictionary, no pair",
        grainPairModels<segregationVelocity>(parse(""), "segregation", mono)
       .size() == 0);
    check("one grain phase: empty diffusion sub-dictionary, no pair",
        grainPairModels<diffusivity>(parse("diffusion { }"), "diffusion", mono)
       .size() == 0);
    expectError("bad input: one grain phase given a segregation pair",
        [&mono]
        {
            grainPairModels<segregationVelocity> p
            (
                parse("segregation { aa { phases (a a); model constant; f 1; } }"),
                "segregation", mono
            );
        },
        {"segregation", "aa", "one grain phase", "(a)"});
    expectError("bad input: two grain phases without a segregation"
        " sub-dictionary", pairs(""), {"segregation", "small", "large"});
}

} // End namespace granularRheologyTest
} // End namespace Foam


// ************************************************************************* //
