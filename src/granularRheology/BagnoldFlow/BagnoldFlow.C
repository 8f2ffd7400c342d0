/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "BagnoldFlow.H"
#include "GrayChugunov.H"
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
    etaAir_(etaAir),
    uTable_(),
    ubarTable_(0)
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

    if (dict.found("phibar"))
    {
        tabulate(rheology, dict);
    }
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::BagnoldFlow::tabulate
(
    const granularRheology& rheology,
    const dictionary& dict
)
{
    const GrayChugunov composition(rheology, h_, cosZeta_, dict);
    const scalar tanZeta = sinZeta_/cosZeta_;
    const scalar c = sqrt(Phi_*g_*cosZeta_);

    const label n = 4000;
    const scalar ds = sqrt(h_)/n;

    // 2 s^2 I/dbar at s_k = k ds, z = h - s^2: (6.1)/(6.3) and (6.6)
    scalarList integrand(n + 1);
    scalarList w(rheology.nGrains(), 0.0);
    forAll(integrand, k)
    {
        const scalar s = k*ds;
        const scalar z = h_ - sqr(s);
        scalar dbar = 0;
        forAll(w, i)
        {
            w[i] = composition.fraction(i, z);
            dbar += w[i]*rheology.d(i);
        }
        integrand[k] = 2*sqr(s)*rheology.inverseFriction(w, tanZeta)/dbar;
    }

    // (6.5) from the base s = sqrt(h) up: u(s_k) = c int_{s_k}^{sqrt h}
    uTable_.setSize(n + 1);
    uTable_[n] = 0;
    for (label k = n - 1; k >= 0; --k)
    {
        uTable_[k] =
            uTable_[k + 1] + c*0.5*ds*(integrand[k] + integrand[k + 1]);
    }

    // ubar = (1/h) int_0^h u dz = (1/h) int_0^sqrt(h) u 2 s ds
    ubarTable_ = 0;
    for (label k = 0; k < n; ++k)
    {
        ubarTable_ +=
            0.5*ds*(2*k*ds*uTable_[k] + 2*(k + 1)*ds*uTable_[k + 1]);
    }
    ubarTable_ /= h_;
}


Foam::scalar Foam::BagnoldFlow::uGrains(const scalar z) const
{
    const scalar zg = min(max(z, scalar(0)), h_);

    if (stratified())
    {
        const label n = uTable_.size() - 1;
        const scalar x = sqrt(h_ - zg)/sqrt(h_)*n;
        const label k = min(label(x), n - 1);
        return uTable_[k] + (x - k)*(uTable_[k + 1] - uTable_[k]);
    }

    // (5.4)
    const scalar c = 2*Izeta_/(3*d_)*sqrt(Phi_*g_*cosZeta_);
    return c*(pow(h_, 1.5) - pow(h_ - zg, 1.5));
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::BagnoldFlow::zeta() const
{
    return atan2(sinZeta_, cosZeta_);
}


Foam::scalar Foam::BagnoldFlow::u(const scalar z) const
{
    const scalar ug = uGrains(z);

    if (z <= h_)
    {
        return ug;
    }

    // (5.7), ERRATA item 4
    const scalar za = min(z, Lz_);
    return
        rhoAir_*g_*sinZeta_/(2*etaAir_)
       *(2*Lz_*(za - h_) + sqr(h_) - sqr(za))
      + ug;
}


Foam::scalar Foam::BagnoldFlow::ubar() const
{
    if (stratified())
    {
        return ubarTable_;
    }

    // (5.16)
    return 2*Izeta_/(5*d_)*sqrt(Phi_*g_*cosZeta_)*pow(h_, 1.5);
}


// ************************************************************************* //
