/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Description
    The checks of each law of every run-time selection table against
    Barker et al. (2021): the friction laws with the coefficients of
    tables 1 and 4, the segregation velocities and the diffusivities.

\*---------------------------------------------------------------------------*/

#include "granularRheologyTest.H"
#include "BarkerGray.H"
#include "wellPosedness.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
namespace granularRheologyTest
{

void testConstantFriction()
{
    autoPtr<frictionLaw> law
    (
        frictionLaw::New(parse("frictionLaw constant; constantCoeffs { mu 0.45; }"))
    );
    bool ok = true;
    for (const scalar I : {0.0, 1e-6, 0.1, 10.0})
    {
        ok = ok && law->mu(I) == 0.45 && law->dmudI(I) == 0;
    }
    check("constant friction: mu(I) = 0.45, dmu/dI = 0", ok);
    check
    (
        "constant friction: ill posed everywhere (2.6)",
        wellPosedness::ranges(*law).empty()
    );
    expectError
    (
        "constant friction: no inverse", [&law]{ law->inverse(0.45); },
        {"inverse"}
    );
}


void testJop()
{
    autoPtr<frictionLaw> law(frictionLaw::New(parse(table1Jop)));
    checkClose("Jop (2.7): mu(0) = mu_s", law->mu(0), 0.342, 1e-15);
    checkClose
    (
        "Jop (2.7): mu(I_0) = (mu_s + mu_d)/2", law->mu(0.069),
        0.5*(0.342 + 0.557), 1e-15
    );
    const scalar I = 0.05, h = 1e-7;
    checkClose
    (
        "Jop: dmu/dI against central difference", law->dmudI(I),
        (law->mu(I + h) - law->mu(I - h))/(2*h), 1e-7
    );
    checkClose
    (
        "Jop: inverse (6.13) of mu(0.05)", law->inverse(law->mu(I)), I, 1e-13
    );

    // Table 1 well-posed range, [0.00397, 0.28016] in the paper,
    // [0.003972, 0.280166] from (2.6) with ERRATA item 1
    const List<Pair<scalar>> r(wellPosedness::ranges(*law));
    check("Jop table 1: one well-posed range", r.size() == 1);
    if (r.size() == 1)
    {
        checkClose("Jop table 1: lower bound 0.003972", r[0].first(), 0.003972, 1e-4);
        checkClose("Jop table 1: upper bound 0.280166", r[0].second(), 0.280166, 1e-5);
        checkClose
        (
            "Jop table 1: lower bound truncates to the paper's 0.00397",
            std::floor(r[0].first()*1e5)/1e5, 0.00397, 1e-12
        );
        checkClose
        (
            "Jop table 1: upper bound truncates to the paper's 0.28016",
            std::floor(r[0].second()*1e5)/1e5, 0.28016, 1e-12
        );
    }

    // Table 4: the lower bound is the paper's I_1 = 0.01886
    checkTable4Bound("Jop", "lower bound 0.01886", 0, 0.01886, 1e-4);
}


void testBarkerGray()
{
    autoPtr<frictionLaw> law(frictionLaw::New(parse(table1BG)));
    const auto& bg = refCast<const frictionLaws::BarkerGray>(*law);
    const scalar I1 = 0.004;

    // A from (2.9), never read: the creep branch meets the high branch
    const scalar muLeft = std::sqrt(1.9/std::log(bg.A()/I1));
    const scalar muRight = (0.342*0.069 + 0.557*I1 + 0.05*sqr(I1))/(0.069 + I1);
    checkClose("BarkerGray (2.8): continuous at I_1", muLeft, muRight, 1e-12);
    checkClose
    (
        "BarkerGray (2.8): mu(I_1) from both sides",
        law->mu(I1*(1 - 1e-14)), law->mu(I1*(1 + 1e-14)), 1e-12
    );
    check("BarkerGray: mu(0) = 0", law->mu(0) == 0);
    check("BarkerGray: mu(-1) = 0, finite", law->mu(-1) == 0);

    bool increasing = true;
    scalar prev = law->mu(1e-8);
    for (label k = 1; k <= 10000; ++k)
    {
        const scalar I = std::pow(10, -8 + 10.0*k/10000);
        const scalar m = law->mu(I);
        increasing = increasing && m > prev;
        prev = m;
    }
    check("BarkerGray: strictly increasing on [1e-8, 100]", increasing);

    checkClose
    (
        "BarkerGray: asymptotically linear, mu(I)/I -> mu_inf",
        law->mu(1e9)/1e9, 0.05, 1e-6
    );
    checkClose
    (
        "BarkerGray: asymptotically linear, dmu/dI -> mu_inf",
        law->dmudI(1e9), 0.05, 1e-6
    );

    for (const scalar I : {1e-3, 0.05, 3.0})
    {
        const scalar h = 1e-6*I;
        checkClose
        (
            "BarkerGray: dmu/dI against central difference at I = "
          + std::to_string(I),
            law->dmudI(I), (law->mu(I + h) - law->mu(I - h))/(2*h), 1e-6
        );
    }

    // (5.6) at 24 degrees: mu(I_zeta) = tan 24
    const scalar tanZeta = std::tan(24*deg);
    const scalar Izeta = law->inverse(tanZeta);
    checkClose("BarkerGray (5.6): mu(I_zeta) = tan 24", law->mu(Izeta), tanZeta, 1e-10);
    checkClose("BarkerGray (5.6): I_zeta(24) = 0.0620", Izeta, 0.0620, 2e-3);
    checkClose
    (
        "BarkerGray: inverse on the creep branch",
        law->mu(law->inverse(0.2)), 0.2, 1e-12
    );

    // Table 1: well posed on [0, 16.9918]
    const List<Pair<scalar>> r(wellPosedness::ranges(*law));
    check("BarkerGray table 1: one well-posed range", r.size() == 1);
    if (r.size() == 1)
    {
        check
        (
            "BarkerGray table 1: well posed down to I = 0",
            r[0].first() == 1e-9 && law->creeps()
            && !wellPosedness::illPosed(law->mu(0), 0)
        );
        checkClose("BarkerGray table 1: I_max = 16.9918", r[0].second(), 16.9918, 5e-5);
    }

    // Table 4: I_max = 16.20
    checkTable4Bound("BarkerGray", "I_max = 16.20", 1, 16.20, 5e-4);
}


void testConstantSegregation()
{
    const onePoint pt;
    const std::string d = "phases (small large); model constant; f 7e-3;";
    checkClose
    (
        "constant segregation: f = 7e-3",
        evalPair("segregation", d, 1e-3, 2e-3, 0, 1, pt), 7e-3, 1e-15
    );
    check
    (
        "constant segregation: same for (nu,lambda) and (lambda,nu)",
        evalPair("segregation", d, 1e-3, 2e-3, 0, 1, pt)
     == evalPair("segregation", d, 1e-3, 2e-3, 1, 0, pt)
    );
}


void testTrewhela()
{
    onePoint pt;
    const std::string d = "phases (small large); model Trewhela;";

    // (3.9) by hand: B rho g gd dbar^2/(C rho g dbar + p) (1 + E/2), R = 2
    checkClose
    (
        "Trewhela (3.9): value at a point (R = 2)",
        evalPair("segregation", d, 1e-3, 2e-3, 0, 1, pt),
        0.0038470209937062163, 1e-13
    );
    check
    (
        "Trewhela: zero at R = 1",
        evalPair("segregation", d, 1e-3, 1e-3, 0, 1, pt) == 0
    );
    check
    (
        "Trewhela: same value for (nu,lambda) and (lambda,nu)",
        evalPair("segregation", d, 1e-3, 2e-3, 0, 1, pt)
     == evalPair("segregation", d, 1e-3, 2e-3, 1, 0, pt)
    );
    const scalar f1 = evalPair("segregation", d, 1e-3, 2e-3, 0, 1, pt);
    pt.shearRate = 30.0;
    checkClose
    (
        "Trewhela: linear in the shear rate",
        evalPair("segregation", d, 1e-3, 2e-3, 0, 1, pt), 3*f1, 1e-14
    );
    pt.shearRate = 10.0;
    // The caller floors p (granularState.p is the floored pressure); C = 0
    // with p = pMin stays finite
    pt.p = 1e-8;
    check
    (
        "Trewhela: C = 0 at p = pMin is finite",
        std::isfinite
        (
            evalPair
            (
                "segregation", d + " TrewhelaCoeffs { C 0; }", 1e-3, 2e-3, 0, 1, pt
            )
        )
    );
}


void testConstantDiffusivity()
{
    const onePoint pt;
    checkClose
    (
        "constant diffusivity: D = 1e-6",
        evalPair
        (
            "diffusion", "phases (small large); model constant; D 1e-6;",
            1e-3, 2e-3, 0, 1, pt
        ), 1e-6, 1e-15
    );
}


void testUtterBehringer()
{
    onePoint pt;
    const std::string d = "phases (small large); model UtterBehringer;";
    checkClose
    (
        "UtterBehringer (3.7): D = A gd dbar^2",
        evalPair("diffusion", d, 1e-3, 2e-3, 0, 1, pt), 2.4300000000000005e-06, 1e-14
    );
    pt.shearRate = 0.0;
    check
    (
        "UtterBehringer: zero without shear",
        evalPair("diffusion", d, 1e-3, 2e-3, 0, 1, pt) == 0
    );
}

} // End namespace granularRheologyTest
} // End namespace Foam


// ************************************************************************* //
