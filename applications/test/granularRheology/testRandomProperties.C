/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Description
    Properties that hold for any parameters in the documented ranges,
    from seeded random draws: the same draws every run.

\*---------------------------------------------------------------------------*/

#include "granularRheologyTest.H"
#include "BarkerGray.H"
#include "segregationVelocity.H"
#include "diffusivity.H"
#include <random>

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
namespace granularRheologyTest
{

//- Draws from [lo, hi] (log-uniform if log), seeded: the same every run
struct draw
{
    std::mt19937_64 gen{20211122};
    scalar operator()(const scalar lo, const scalar hi, const bool log = false)
    {
        const scalar u = std::uniform_real_distribution<scalar>(0, 1)(gen);
        return log
            ? lo*std::pow(hi/lo, u)
            : lo + (hi - lo)*u;
    }
};

//- A friction law with random coefficients in the documented valid ranges
//  (k: 0 constant, 1 Jop, 2 BarkerGray)
std::string randomLaw(draw& r, const label k)
{
    std::ostringstream os;
    os.precision(17);
    const scalar mus = r(0.1, 0.7);
    const scalar mud = mus + r(0.01, 0.5);
    if (k == 0)
    {
        os << "frictionLaw constant; constantCoeffs { mu " << mus << "; }";
    }
    else if (k == 1)
    {
        os << "frictionLaw Jop; JopCoeffs { mus " << mus << "; mud " << mud
           << "; I0 " << r(0.01, 1, true) << "; }";
    }
    else
    {
        os << "frictionLaw BarkerGray; BarkerGrayCoeffs { mus " << mus
           << "; mud " << mud << "; muInf " << r(0, 0.1) << "; I0 "
           << r(0.01, 1, true) << "; alpha " << r(1.5, 2.5) << "; I1 "
           << r(1e-3, 0.05, true) << "; }";
    }
    return os.str();
}

//- Failures of one random property: their count and the first one's input
struct failures
{
    label n = 0;
    std::string first;

    void add(const std::string& what)
    {
        if (first.empty())
        {
            first = what.substr(0, 400);
        }
        ++n;
    }
};

//- A random mixture of three grain phases of diameters d (drawn here,
//  increasing) with viscosity cap etaMax: its granularProperties entries
std::string randomMixture(draw& r, scalar d[3], const scalar etaMax)
{
    d[0] = r(1e-4, 1e-2, true);
    d[1] = d[0]*r(1, 3);
    d[2] = d[1]*r(1, 3);
    std::ostringstream os;
    os.precision(17);
    os << "rhoStar " << r(500, 5000) << "; Phi " << r(0.4, 0.7)
       << "; etaMax " << etaMax << "; pMin " << r(1e-10, 1e-4, true)
       << "; mixtureRule ";
    // (3.4) averages the coefficients of one law: the same for all
    const bool weightedParameters = r(0, 1) < 0.5;
    const label k0 = label(r(0, 3)) % 3;
    os << (weightedParameters ? "weightedParameters" : "weightedFriction")
       << "; grains {";
    for (label i = 0; i < 3; ++i)
    {
        const label k = weightedParameters ? k0 : label(r(0, 3)) % 3;
        os << " g" << i << " { d " << d[i] << "; " << randomLaw(r, k)
           << " }";
    }
    os << " }";
    return os.str();
}

//- n random states: the fractions a of three grain phases (some cells
//  without grains), p (some 0, some < 0), |D| (some 0) and the gradients
//  of the fractions
struct randomStates
{
    scalarField a[3];
    scalarField p, normD;
    scalarField grad[3];

    randomStates(draw& r, const label n)
    :
        a{scalarField(n), scalarField(n), scalarField(n)},
        p(n),
        normD(n),
        grad{scalarField(n), scalarField(n), scalarField(n)}
    {
        for (label c = 0; c < n; ++c)
        {
            const scalar grains = c % 10 == 0 ? 0 : r(0, 1);
            const scalar x = r(0, 1), y = r(0, 1 - x);
            a[0][c] = grains*x;
            a[1][c] = grains*y;
            a[2][c] = grains - a[0][c] - a[1][c];
            p[c] =
                c % 7 == 0 ? 0 : c % 11 == 0 ? -r(0, 100) : r(1e-6, 1e5, true);
            normD[c] = c % 5 == 0 ? 0 : r(1e-6, 1e3, true);
            for (label i = 0; i < 3; ++i)
            {
                grad[i][c] = r(-1e3, 1e3);
            }
        }
    }
};

//- The rheology chain at the states: dbar, I, mu, eta finite (bad), eta in
//  [0, etaMax] (cap); returns the pressure seen by the rheology
scalarField checkChain
(
    const granularRheology& rheology,
    const randomStates& s,
    const UPtrList<const scalarField>& w,
    const scalar etaMax,
    const std::string& props,
    failures& bad,
    failures& cap,
    scalarField& dbar
)
{
    const label n = s.p.size();
    scalarField I(n), mu(n), eta(n), pf(n);
    rheology.meanDiameter(w, dbar);
    rheology.inertialNumber(s.normD, s.p, dbar, I);
    rheology.friction(I, w, mu);
    rheology.viscosity(mu, s.p, s.normD, eta);
    forAll(s.p, c)
    {
        pf[c] = rheology.pressure(s.p[c]);
        if
        (
            !std::isfinite(I[c]) || I[c] < 0 || !std::isfinite(mu[c])
         || mu[c] < 0 || !std::isfinite(eta[c]) || !std::isfinite(dbar[c])
        )
        {
            bad.add(props);
        }
        if (eta[c] < 0 || eta[c] > etaMax)
        {
            cap.add("eta outside [0, etaMax]: " + props);
        }
    }
    return pf;
}

//- Random segregation and diffusion laws (Trewhela or constant,
//  UtterBehringer or constant) for every ordered pair, evaluated
//  separately at the state: F[i][j], D[i][j], each finite and >= 0 (pair)
void pairLaws
(
    draw& r,
    const granularRheology& rheology,
    const granularState& state,
    scalarField F[3][3],
    scalarField D[3][3],
    const std::string& props,
    failures& pair
)
{
    std::ostringstream tw;
    tw.precision(17);
    tw << "model Trewhela; TrewhelaCoeffs { B " << r(0, 2) << "; C "
       << r(0, 1) << "; E " << r(0, 5) << "; }";
    std::ostringstream ub;
    ub.precision(17);
    ub << "model UtterBehringer; UtterBehringerCoeffs { A "
       << r(1e-3, 1) << "; }";
    const std::string seg = r(0, 1) < 0.5
        ? tw.str() : "model constant; f " + std::to_string(r(0, 1)) + ";";
    const std::string dif = r(0, 1) < 0.5
        ? ub.str() : "model constant; D " + std::to_string(r(0, 1e-3)) + ";";

    const label n = state.shearRate.size();
    for (label i = 0; i < 3; ++i)
    {
        for (label j = 0; j < 3; ++j)
        {
            F[i][j] = scalarField(n, 0);
            D[i][j] = scalarField(n, 0);
            if (i == j)
            {
                continue;
            }
            const std::string phases = "phases (g" + std::to_string(i)
              + " g" + std::to_string(j) + "); ";
            segregationVelocity::New(parse(phases + seg), rheology, i, j)
                ->f(state, F[i][j]);
            diffusivity::New(parse(phases + dif), rheology, i, j)
                ->D(state, D[i][j]);
            forAll(F[i][j], c)
            {
                if
                (
                    !std::isfinite(F[i][j][c]) || F[i][j][c] < 0
                 || !std::isfinite(D[i][j][c]) || D[i][j][c] < 0
                )
                {
                    pair.add("pair law: " + props + " " + seg + " " + dif);
                }
            }
        }
    }
}

//- (2.13): phase i moves along g relative to j with f_ij phi_i phi_j if
//  smaller, against it if larger; (2.15): D_ij (phi_j grad phi_i - phi_i
//  grad phi_j).  Each summed over the phases: zero (2.12) in every state
void checkFluxSums
(
    const scalar d[3],
    const randomStates& s,
    const scalarField F[3][3],
    const scalarField D[3][3],
    const std::string& props,
    failures& sum
)
{
    forAll(s.p, c)
    {
        scalar segSum = 0, segScale = 0, difSum = 0, difScale = 0;
        for (label i = 0; i < 3; ++i)
        {
            for (label j = 0; j < 3; ++j)
            {
                if (i == j)
                {
                    continue;
                }
                const scalar sign = d[i] < d[j] ? 1 : d[i] > d[j] ? -1 : 0;
                const scalar fs = sign*F[i][j][c]*s.a[i][c]*s.a[j][c];
                const scalar fd = D[i][j][c]
                   *(s.a[j][c]*s.grad[i][c] - s.a[i][c]*s.grad[j][c]);
                segSum += fs;
                segScale += mag(fs);
                difSum += fd;
                difScale += mag(fd);
            }
        }
        if (mag(segSum) > 1e-14*segScale || mag(difSum) > 1e-14*difScale)
        {
            sum.add("fluxes do not sum to zero: " + props);
        }
    }
}

//- 200 random mixtures of three grain phases, each at 50 random states
//  (fractions, pressure including 0 and < 0, |D| including 0): I, mu and
//  eta finite, 0 <= eta <= etaMax (4.12); every segregation velocity and
//  diffusivity finite and >= 0; and the pairwise fluxes of (2.13) and
//  (2.15) built from the laws evaluated for (nu, lambda) and (lambda, nu)
//  separately sum to zero over the phases (2.12)
void testRandomProperties()
{
    draw r;
    const label nMixtures = 200;
    const label n = 50;
    failures nBad, nCap, nPair, nSum;

    for (label m = 0; m < nMixtures; ++m)
    {
        const scalar etaMax = r(1e-2, 1e4, true);
        scalar d[3];
        const std::string props(randomMixture(r, d, etaMax));
        const granularRheology rheology(parse(props));

        const randomStates s(r, n);
        UPtrList<const scalarField> alphas(3);
        for (label i = 0; i < 3; ++i)
        {
            alphas.set(i, &s.a[i]);
        }
        PtrList<scalarField> w;
        rheology.grainFractions(alphas, w);
        UPtrList<const scalarField> wp(3);
        for (label i = 0; i < 3; ++i)
        {
            wp.set(i, &w[i]);
        }
        scalarField dbar(n);
        const scalarField pf
        (
            checkChain
            (
                rheology, s, wp, etaMax,
                "mixture " + std::to_string(m) + ": " + props, nBad, nCap,
                dbar
            )
        );

        const scalarField shearRate(2*s.normD);
        const granularState state{shearRate, pf, dbar, wp, r(1, 20)};
        scalarField F[3][3], D[3][3];
        pairLaws(r, rheology, state, F, D, props, nPair);
        checkFluxSums(d, s, F, D, props, nSum);
    }

    const std::pair<std::string, const failures&> properties[] =
    {
        {"random: 10000 states of 200 mixtures give finite dbar, I, mu, eta", nBad},
        {"random: 0 <= eta <= etaMax (4.12) in all 10000 states", nCap},
        {"random: segregation velocities and diffusivities finite and >= 0", nPair},
        {"random: the pairwise fluxes (2.13), (2.15) sum to zero (2.12)", nSum},
    };
    for (const auto& property : properties)
    {
        check
        (
            property.first, property.second.n == 0,
            std::to_string(property.second.n) + " failed, first: "
          + property.second.first
        );
    }
}

} // End namespace granularRheologyTest
} // End namespace Foam


// ************************************************************************* //
