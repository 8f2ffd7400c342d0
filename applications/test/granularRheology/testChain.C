/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Description
    The rheology chain of the mixture (2.3)-(2.11), and the stratified
    inflow of section 6.1 against (6.3) and (5.8)-(5.11).

\*---------------------------------------------------------------------------*/

#include "granularRheologyTest.H"
#include "GrayChugunov.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
namespace granularRheologyTest
{

void testChain()
{
    const granularRheology rheology(parse(properties(1e-3, 2e-3)));

    // Points: pure small, 50:50, 25:25 with 50 % air, pure air
    scalarField as({1, 0.5, 0.25, 0});
    scalarField al({0, 0.5, 0.25, 0});
    UPtrList<const scalarField> alphas(2);
    alphas.set(0, &as);
    alphas.set(1, &al);

    PtrList<scalarField> w;
    rheology.grainFractions(alphas, w);
    UPtrList<const scalarField> wp(2);
    wp.set(0, &w[0]);
    wp.set(1, &w[1]);

    scalarField dbar(4);
    rheology.meanDiameter(wp, dbar);
    checkClose("(3.1) dbar, pure small", dbar[0], 1e-3, 1e-15);
    checkClose("(3.1) dbar, 50:50", dbar[1], 1.5e-3, 1e-15);
    checkClose("(3.1) dbar normalised by the grain fraction (air 50 %)", dbar[2], 1.5e-3, 1e-15);
    check("(3.1) dbar finite in pure air", std::isfinite(dbar[3]) && dbar[3] > 0);

    // (2.4) on simple shear u = (gd z, 0, 0): |D| = gd/2
    symmTensorField D(1, symmTensor(0, 0, 0.5*7.0, 0, 0, 0));
    scalarField normD(1);
    granularRheology::strainRateNorm(D, normD);
    checkClose("(2.4) |D| of simple shear = shear rate/2", normD[0], 3.5, 1e-15);

    // (3.2)
    scalarField I(1), p1(1, 100.0), nD1(1, 3.5), d1(1, 1.5e-3);
    rheology.inertialNumber(nD1, p1, d1, I);
    checkClose("(3.2) I = 2 dbar |D|/std::sqrt(p/rho*)", I[0], 2*1.5e-3*3.5/std::sqrt(100.0/2500), 1e-15);

    // (2.3) uncapped, and (4.12)
    scalarField mu1(1, 0.4), eta(1);
    rheology.viscosity(mu1, p1, nD1, eta);
    checkClose("(2.3) eta = mu p/(2|D|)", eta[0], 0.4*100/(2*3.5), 1e-15);

    // Degenerate states: |D| = 0, p = 0, p < 0, pure air, pure grains
    scalarField nDs({0, 1, 1, 0, 1, 1e-300});
    scalarField ps({100, 0, -50, 0, 1e6, 1e5});
    scalarField asD({1, 1, 0.5, 0, 0, 0.3});
    scalarField alD({0, 0, 0.5, 0, 1, 0.7});
    UPtrList<const scalarField> aD(2);
    aD.set(0, &asD);
    aD.set(1, &alD);
    PtrList<scalarField> wD;
    rheology.grainFractions(aD, wD);
    UPtrList<const scalarField> wDp(2);
    wDp.set(0, &wD[0]);
    wDp.set(1, &wD[1]);
    scalarField dD(6), ID(6), muD(6), dmuD(6), etaD(6);
    rheology.meanDiameter(wDp, dD);
    rheology.inertialNumber(nDs, ps, dD, ID);
    rheology.friction(ID, wDp, muD, &dmuD);
    rheology.viscosity(muD, ps, nDs, etaD);
    bool finite = true, capped = true;
    forAll(etaD, i)
    {
        finite = finite && std::isfinite(ID[i]) && std::isfinite(muD[i])
            && std::isfinite(etaD[i]) && etaD[i] >= 0;
        capped = capped && etaD[i] <= 10;
    }
    check("viscosity finite for |D| = 0, p = 0, p < 0, pure air, pure grains", finite);
    check("viscosity <= etaMax in all those states", capped);
    check("viscosity = etaMax at |D| = 0 under pressure", etaD[0] == 10);

    // (3.3) against the phases' own laws, and (3.4) against the law with
    // averaged coefficients
    const std::string lawS =
        "frictionLaw Jop; JopCoeffs { mus 0.3; mud 0.6; I0 0.1; }";
    const std::string lawL =
        "frictionLaw Jop; JopCoeffs { mus 0.5; mud 0.7; I0 0.3; }";
    const std::string mixed =
        "rhoStar 2500; Phi 0.6; etaMax 10; grains { small { d 1e-3; " + lawS
      + " } large { d 2e-3; " + lawL + " } }";
    scalarField Im(1, 0.2), mu(1), ws(1, 0.25), wl(1, 0.75);
    UPtrList<const scalarField> wm(2);
    wm.set(0, &ws);
    wm.set(1, &wl);
    {
        const granularRheology r(parse("mixtureRule weightedFriction; " + mixed));
        r.friction(Im, wm, mu);
        checkClose
        (
            "(3.3) weighted friction",
            mu[0],
            0.25*frictionLaw::New(parse(lawS))->mu(0.2)
          + 0.75*frictionLaw::New(parse(lawL))->mu(0.2),
            1e-15
        );
    }
    {
        const granularRheology r(parse("mixtureRule weightedParameters; " + mixed));
        r.friction(Im, wm, mu);
        checkClose
        (
            "(3.4) weighted parameters",
            mu[0],
            frictionLaw::New
            (
                parse("frictionLaw Jop; JopCoeffs { mus 0.45; mud 0.675; I0 0.25; }")
            )->mu(0.2),
            1e-14
        );
    }
}


//- Section 6.1: the mixture's inverse friction against (6.3), and the
//  Gray-Chugunov composition (5.8)-(5.11) of the stratified inflow
void testStratified()
{
    // Table 1 Jop for the small grains, mu_s^l = 1.2 mu_s for the large
    const std::string large =
        "frictionLaw Jop; JopCoeffs { mus 0.4104; mud 0.557; I0 0.069; }";
    const std::string pairs =
        " segregation { sl { phases (small large); model constant; f 7e-3; } }"
        " diffusion { sl { phases (small large); model constant; D 1e-6; } }";
    const scalar tanZeta = std::tan(24*deg);
    for (const word rule : {"weightedFriction", "weightedParameters"})
    {
        std::ostringstream os;
        os  << "rhoStar 2500; Phi 0.6; etaMax 10; mixtureRule " << rule
            << "; grains { small { d 0.5e-3; " << table1Jop << " }"
            << " large { d 0.5e-3; " << large << " } }" << pairs;
        const granularRheology rheology(parse(os.str()));
        const scalar ws = 0.3;
        const scalar mus = ws*0.342 + (1 - ws)*0.4104;
        checkClose
        (
            "(6.3) I of a 30:70 Jop mixture at 24 deg, " + rule,
            rheology.inverseFriction({ws, 1 - ws}, tanZeta),
            0.069*(tanZeta - mus)/(0.557 - tanZeta), 1e-12
        );
        checkClose
        (
            "(5.5) inverse friction of a pure phase = its law's, " + rule,
            rheology.inverseFriction({0, 1}, tanZeta),
            rheology.law(1).inverse(tanZeta), 1e-15
        );
    }

    std::ostringstream os;
    os  << "rhoStar 2500; Phi 0.6; etaMax 10; grains { small { d 0.5e-3; "
        << table1Jop << " } large { d 0.5e-3; " << large << " } }" << pairs;
    const granularRheology rheology(parse(os.str()));
    const scalar h = 5e-3;
    const GrayChugunov gc(rheology, h, std::cos(24*deg), parse("phibar 0.5;"));
    checkClose("(5.9) Pe of table 3 at 24 deg = 31.97", gc.Pe(), 31.97, 2e-4);

    // (5.10): the depth average is phibar (Simpson, 2000 intervals)
    const label n = 2000;
    scalar sum = 0;
    for (label k = 0; k <= n; ++k)
    {
        const scalar wgt = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
        sum += wgt*gc.phiSmall(h*k/n);
    }
    checkClose("(5.10) depth average of (5.8) = phibar 0.5", sum/(3*n), 0.5, 1e-9);
    checkClose
    (
        "(5.8) phi^s = 1/2 at mid-depth for phibar = 1/2 (symmetry)",
        gc.phiSmall(0.5*h), 0.5, 1e-12
    );
    check
    (
        "(5.8) small grains at the base, large at the surface",
        gc.phiSmall(0) > 0.99 && gc.phiSmall(h) < 0.01
     && gc.fraction(1, h) == 1 - gc.phiSmall(h)
    );

    std::ostringstream bad;
    bad << "rhoStar 2500; Phi 0.6; etaMax 10; grains { small { d 1e-3; "
        << table1Jop << " } large { d 1.5e-3; " << table1Jop << " } }"
        << " segregation { sl { phases (small large); model Trewhela; } }"
        << " diffusion { sl { phases (small large); model constant; D 1e-6; } }";
    expectError
    (
        "(5.8) refused for a Trewhela pair (constant f and D only)",
        [&]()
        {
            const granularRheology r(parse(bad.str()));
            GrayChugunov(r, h, 1, parse("phibar 0.5;"));
        },
        {"model", "Trewhela", "constant"}
    );
    expectError
    (
        "(5.8) refused for one grain phase",
        [&]()
        {
            const granularRheology r
            (
                parse("rhoStar 2500; Phi 0.6; etaMax 10; grains { grains"
                    " { d 1e-3; " + table1Jop + " } }")
            );
            GrayChugunov(r, h, 1, parse("phibar 0.5;"));
        },
        {"phibar", "0.5", "bidisperse", "1 grain phase(s)", "grains"}
    );
    expectError
    (
        "(5.8) refused for phibar = 1",
        [&]() { GrayChugunov(rheology, h, 1, parse("phibar 1;")); },
        {"phibar", "1"}
    );
}

} // End namespace granularRheologyTest
} // End namespace Foam


// ************************************************************************* //
