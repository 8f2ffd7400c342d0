/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularMixture.H"
#include "wellPosedness.H"
#include "fvcGrad.H"
#include "zeroGradientFvPatchFields.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(granularMixture, 0);
}


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

Foam::IOobject Foam::granularMixture::stateIO
(
    const word& name,
    const bool write
) const
{
    return IOobject
    (
        name,
        mesh_.time().timeName(),
        mesh_,
        IOobject::NO_READ,
        write ? IOobject::AUTO_WRITE : IOobject::NO_WRITE
    );
}


Foam::tmp<Foam::volScalarField> Foam::granularMixture::zeroState
(
    const dimensionSet& dims
) const
{
    return tmp<volScalarField>::New
    (
        IOobject
        (
            "zeroState",
            mesh_.time().timeName(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            false
        ),
        mesh_,
        dimensionedScalar(dims, Zero),
        zeroGradientFvPatchScalarField::typeName
    );
}


void Foam::granularMixture::calcMixture()
{
    const volScalarField& alphaAir = phases_.air();
    const dimensionedScalar rhoGrains(rheology_.rhoGrains());

    // (4.7a,b): the grains share one density and one viscosity
    rho_ = alphaAir*air_.rho() + (1 - alphaAir)*rhoGrains;
    eta_ = alphaAir*air_.eta() + (1 - alphaAir)*etaGranular_;
    nu_ = eta_/rho_;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularMixture::granularMixture
(
    const volVectorField& U,
    const surfaceScalarField& phi
)
:
    IOdictionary
    (
        IOobject
        (
            "granularProperties",
            U.time().constant(),
            U.db(),
            IOobject::MUST_READ_IF_MODIFIED,
            IOobject::NO_WRITE
        )
    ),
    transportModel(),
    mesh_(U.mesh()),
    U_(U),
    phi_(phi),
    gravity_(mesh_, *this),
    rheology_(*this),
    pairFluxes_(mesh_, *this, rheology_),
    air_(*this, gravity_),
    phases_(mesh_, *this, air_.name(), rheology_),
    transport_(phi, phases_, pairFluxes_, air_, gravity_, rheology_),
    timeStep_(mesh_),
    pressure_(*this, phases_, air_, gravity_),
    pGranular_(stateIO("pGranular", true), zeroState(dimPressure)),
    shearRate_(stateIO("shearRate", true), zeroState(inv(dimTime))),
    dbar_(stateIO("dbar", true), zeroState(dimLength)),
    I_(stateIO("I", true), zeroState(dimless)),
    etaGranular_(stateIO("etaGranular", true), zeroState(dimPressure*dimTime)),
    illPosed_(stateIO("illPosed", true), zeroState(dimless)),
    rho_(stateIO("granularMixture:rho", false), zeroState(dimDensity)),
    eta_(stateIO("granularMixture:eta", false), zeroState(dimPressure*dimTime)),
    nu_(stateIO("granularMixture:nu", false), zeroState(dimViscosity))
{
    // The density of the initial fractions: createFields.H builds p as
    // p_rgh + rho*gh before the first rheology, which evaluates with that p
    calcMixture();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::granularMixture::cflParts Foam::granularMixture::cfl
(
    const scalar deltaT,
    const bool viscousLimit
)
{
    const tmp<scalarField> diffusion
    (
        pairFluxes_.diffusionRate(timeStep_.G())
    );
    const granularTimeStep::rates r
    {
        nu_.primitiveField(), transport_.segregationRate(), diffusion()
    };
    return timeStep_.cfl
    (
        deltaT, viscousLimit, phi_, r, transport_.maxSubCycles()
    );
}


Foam::label Foam::granularMixture::nAlphaSubCycles()
{
    const scalar deltaT = mesh_.time().deltaTValue();
    return transport_.nSubCycles
    (
        transport_.maxSubCycles() ? cfl(deltaT, false).transport : 0
    );
}


void Foam::granularMixture::correctRheology
(
    const volScalarField& p,
    const bool closed
)
{
    const label nCells = mesh_.nCells();

    pGranular_.primitiveFieldRef() =
        max(pressure_.seenByRheology(p, closed), rheology_.pMin().value());
    pGranular_.correctBoundaryConditions();

    // (2.4): |D| of the previous iterate of U, shear rate 2|D|
    scalarField normD(nCells);
    rheology_.strainRateNorm(symm(fvc::grad(U_))().primitiveField(), normD);
    shearRate_.primitiveFieldRef() = 2*normD;

    // Grain-volume fractions and (3.1)
    PtrList<scalarField> w;
    phases_.grainFractions(w);
    UPtrList<const scalarField> wc(w.size());
    forAll(w, k)
    {
        wc.set(k, &w[k]);
    }
    rheology_.meanDiameter(wc, dbar_.primitiveFieldRef());

    // (3.2), (3.3)/(3.4), (2.3) with (4.12), and (2.6)
    const scalarField& pg = pGranular_.primitiveField();
    rheology_.inertialNumber
    (
        normD, pg, dbar_.primitiveField(), I_.primitiveFieldRef()
    );

    scalarField mu(nCells);
    scalarField dmudI(nCells);
    rheology_.friction(I_.primitiveField(), wc, mu, &dmudI);
    rheology_.viscosity(mu, pg, normD, etaGranular_.primitiveFieldRef());
    wellPosedness::indicator
    (
        I_.primitiveField(), mu, dmudI, illPosed_.primitiveFieldRef()
    );

    // Segregation and diffusion of the grain pairs (section 3.3)
    pairFluxes_.correct
    (
        granularState
        {
            shearRate_.primitiveField(), pg, dbar_.primitiveField(), wc,
            mag(gravity_.g().value())
        }
    );

    for
    (
        volScalarField* fld
      : {&shearRate_, &dbar_, &I_, &etaGranular_, &illPosed_}
    )
    {
        fld->correctBoundaryConditions();
    }

    calcMixture();
}


void Foam::granularMixture::solve()
{
    const label nSub = nAlphaSubCycles();
    if (transport_.maxSubCycles())
    {
        Info<< "Phase transport: " << nSub << " sub-cycles" << endl;
    }

    transport_.solve(nSub);
    phases_.reportBounds();

    calcMixture();
}


bool Foam::granularMixture::read()
{
    if (regIOobject::read())
    {
        // Everything again, with the checks of the start; the phases,
        // whose fields are read at the start only, cannot change
        air_.read(*this, gravity_);
        pressure_.read(*this);
        rheology_.read(*this);
        pairFluxes_.read(*this, rheology_);

        Info<< "Re-read " << objectPath() << ": the air, the rheology,"
            << " the segregation and the diffusion laws" << nl << endl;
        return true;
    }
    return false;
}


// ************************************************************************* //
