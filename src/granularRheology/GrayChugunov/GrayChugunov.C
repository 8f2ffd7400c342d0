/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "GrayChugunov.H"
#include "grainPairModels.H"
#include "segregationVelocity.H"
#include "diffusivity.H"
#include "granularState.H"
#include "granularInput.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::GrayChugunov::GrayChugunov
(
    const granularRheology& rheology,
    const scalar h,
    const scalar cosZeta,
    const dictionary& dict
)
:
    h_(h),
    phibar_(dict.get<scalar>("phibar")),
    Pe_(0),
    logA_(0),
    small_(0),
    large_(1)
{
    if (!(phibar_ > 0 && phibar_ < 1))
    {
        granularInput::invalid
        (
            dict, "phibar", phibar_,
            "the depth-averaged small-grain fraction of (5.10), in (0, 1)"
        );
    }
    if (rheology.nGrains() != 2)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'phibar' in dictionary "
            << dict.name() << ": phibar = " << phibar_ << " asks for the"
            << " Gray-Chugunov composition (5.8), which is bidisperse, but "
            << rheology.dict().name() << " has " << rheology.nGrains()
            << " grain phase(s) " << flatOutput(rheology.names()) << nl
            << exit(FatalIOError);
    }

    const grainPairModels<segregationVelocity> segregation
    (
        rheology.dict(), "segregation", rheology
    );
    const grainPairModels<diffusivity> diffusion
    (
        rheology.dict(), "diffusion", rheology
    );
    const grainPairModel* pairs[] = {&segregation[0], &diffusion[0]};
    for (const grainPairModel* m : pairs)
    {
        const word model(m->dict().get<word>("model"));
        if (model != "constant")
        {
            FatalIOErrorInFunction(m->dict())
                << "Invalid value of keyword 'model' in dictionary "
                << m->dict().name() << ": model = " << model
                << " (the Gray-Chugunov composition (5.8) asked for by "
                << dict.name() << " holds for constant segregation velocity"
                << " and diffusivity: model constant)" << nl
                << exit(FatalIOError);
        }
    }
    small_ = segregation[0].small();
    large_ = segregation[0].large();

    // The constant models do not depend on the state: any one point serves
    const scalarField one(1, 1.0);
    UPtrList<const scalarField> w(2);
    w.set(0, &one);
    w.set(1, &one);
    const granularState state{one, one, one, w, 1.0};
    scalarField f(1), D(1);
    segregation[0].f(state, f);
    diffusion[0].D(state, D);
    if (!(f[0] > 0 && D[0] > 0))
    {
        FatalIOErrorInFunction(dict)
            << "The Gray-Chugunov composition (5.8) in " << dict.name()
            << " needs f > 0 and D > 0 for the pair (" << rheology.names()
            << "): f = " << f[0] << ", D = " << D[0] << nl
            << exit(FatalIOError);
    }

    Pe_ = peclet(f[0], h_, cosZeta, D[0]);

    // log of (5.11), without overflow or cancellation
    logA_ =
        -Pe_*phibar_
      + std::log1p(-std::exp(-Pe_*(1 - phibar_)))
      - std::log(-std::expm1(-Pe_*phibar_));
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::GrayChugunov::peclet
(
    const scalar f,
    const scalar h,
    const scalar cosZeta,
    const scalar D
)
{
    // (5.9)
    return f*h*cosZeta/D;
}


Foam::scalar Foam::GrayChugunov::phiSmall(const scalar z) const
{
    // (5.8), as a logistic function of log A + Pe zhat
    const scalar zHat = min(max(z, scalar(0)), h_)/h_;
    const scalar x = logA_ + Pe_*zHat;
    return x > 0 ? std::exp(-x)/(1 + std::exp(-x)) : 1/(1 + std::exp(x));
}


Foam::scalar Foam::GrayChugunov::fraction(const label i, const scalar z) const
{
    const scalar phiS = phiSmall(z);
    return i == small_ ? phiS : 1 - phiS;
}


// ************************************************************************* //
