/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "BagnoldFlow.H"
#include "granularInput.H"
#include "unitConversion.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::BagnoldFlow::BagnoldFlow
(
    const granularRheology& rheology,
    const word& phase,
    const vector& g,
    const vector& normal,
    const scalar h,
    const scalar Lz,
    const scalar rhoAir,
    const scalar etaAir,
    const dictionary& dict
)
:
    h_(h),
    Lz_(Lz),
    ex_(Zero),
    g_(mag(g)),
    cosZeta_(0),
    sinZeta_(0),
    d_(0),
    Phi_(rheology.Phi().value()),
    Izeta_(0),
    rhoAir_(rhoAir),
    etaAir_(etaAir)
{
    const label i = rheology.index(phase);
    if (i < 0)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'phase' in dictionary "
            << dict.name() << ": phase = " << phase
            << " (a grain phase of " << rheology.dict().name() << ": "
            << rheology.names() << ")" << nl << exit(FatalIOError);
    }
    if (mag(normal) < SMALL)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'normal' in dictionary "
            << dict.name() << ": normal = " << normal
            << " (a vector of nonzero length)" << nl << exit(FatalIOError);
    }
    if (h_ <= 0 || Lz_ < h_)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'h' in dictionary " << dict.name()
            << ": h = " << h_ << " (0 < h <= " << Lz_
            << ", the top of the patch above the base)" << nl
            << exit(FatalIOError);
    }

    const vector n(normal/mag(normal));
    const vector gt(g - (g & n)*n);
    cosZeta_ = -(g & n)/max(g_, VSMALL);
    sinZeta_ = mag(gt)/max(g_, VSMALL);
    if (cosZeta_ <= 0 || mag(gt) < SMALL*g_)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'normal' in dictionary "
            << dict.name() << ": normal = " << normal << " with g = " << g
            << " (the plane must be inclined: 0 < zeta < 90 degrees)" << nl
            << exit(FatalIOError);
    }
    ex_ = gt/mag(gt);

    d_ = rheology.d(i);

    // (5.5)
    Izeta_ = rheology.law(i).inverse(sinZeta_/cosZeta_);
    if (!(Izeta_ > 0) || !std::isfinite(Izeta_))
    {
        FatalIOErrorInFunction(dict)
            << "No steady uniform flow of phase " << phase << " at zeta = "
            << radToDeg(zeta()) << " degrees: mu^{-1}(tan zeta) = " << Izeta_
            << " (tan zeta must lie inside the range of the friction law)"
            << nl << exit(FatalIOError);
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::BagnoldFlow::zeta() const
{
    return atan2(sinZeta_, cosZeta_);
}


Foam::scalar Foam::BagnoldFlow::u(const scalar z) const
{
    // (5.4)
    const scalar c = 2*Izeta_/(3*d_)*sqrt(Phi_*g_*cosZeta_);
    const scalar zg = min(max(z, scalar(0)), h_);
    const scalar uGrains = c*(pow(h_, 1.5) - pow(h_ - zg, 1.5));

    if (z <= h_)
    {
        return uGrains;
    }

    // (5.7), ERRATA item 4
    const scalar za = min(z, Lz_);
    return
        rhoAir_*g_*sinZeta_/(2*etaAir_)
       *(2*Lz_*(za - h_) + sqr(h_) - sqr(za))
      + uGrains;
}


Foam::scalar Foam::BagnoldFlow::ubar() const
{
    // (5.16)
    return 2*Izeta_/(5*d_)*sqrt(Phi_*g_*cosZeta_)*pow(h_, 1.5);
}


// ************************************************************************* //
