/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularPressure.H"
#include "granularPhases.H"
#include "granularAir.H"
#include "granularGravity.H"
#include "granularInput.H"

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{
    //- tensionWarning [Pa] of granularProperties (>= 0, default 1)
    Foam::dimensionedScalar readTensionWarning(const Foam::dictionary& dict)
    {
        using namespace Foam;
        return granularInput::readNonNegativeOrDefault
        (
            dict, "tensionWarning", dimPressure, 1
        );
    }
}


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

Foam::tmp<Foam::scalarField> Foam::granularPressure::airReduced
(
    const volScalarField& p
) const
{
    return
        p.primitiveField()
      - air_.rho().value()
       *(gravity_.hydrostatic().value() & mesh_.C().primitiveField());
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularPressure::granularPressure
(
    const dictionary& dict,
    const granularPhases& phases,
    const granularAir& air,
    const granularGravity& gravity
)
:
    mesh_(phases.air().mesh()),
    phases_(phases),
    air_(air),
    gravity_(gravity),
    dictName_(dict.name().name()),
    tensionWarning_(readTensionWarning(dict)),
    grainPressureMin_
    (
        IOobject
        (
            "grainPressureMin",
            mesh_.time().constant(),
            mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE
        ),
        dimensionedScalar("grainPressureMin", dimPressure, VGREAT)
    )
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::granularPressure::airLevel(const volScalarField& p) const
{
    // The mean of p - rho^a g.x over the pure-air cells
    const scalarField pAir(airReduced(p));
    const scalarField V
    (
        mesh_.V().field()*pos0(phases_.air().primitiveField() - 0.99)
    );
    const scalar volAir = gSum(V);
    if (volAir > 0)
    {
        return gSum(V*pAir)/volAir;
    }

    // No air (a domain full of grains): the smallest value, so that the
    // grains' pressure vanishes where it is lowest, as under a free surface,
    // and is positive elsewhere
    return gMin(pAir);
}


void Foam::granularPressure::level
(
    volScalarField& p,
    volScalarField& p_rgh,
    const scalar pRefValue
) const
{
    const dimensionedScalar shift
    (
        "shift",
        p.dimensions(),
        pRefValue - airLevel(p)
    );
    p += shift;
    p_rgh += shift;
}


Foam::tmp<Foam::scalarField> Foam::granularPressure::seenByRheology
(
    const volScalarField& p,
    const bool closed
) const
{
    if (!closed)
    {
        return tmp<scalarField>::New(p.primitiveField());
    }
    return airReduced(p) - airLevel(p);
}


Foam::scalar Foam::granularPressure::report
(
    const volScalarField& p,
    const bool closed
)
{
    const scalarField pg(seenByRheology(p, closed));
    const scalarField& air = phases_.air().primitiveField();
    scalar lowest = GREAT;
    forAll(pg, celli)
    {
        if (air[celli] < 0.5)
        {
            lowest = min(lowest, pg[celli]);
        }
    }
    reduce(lowest, minOp<scalar>());
    if (lowest == GREAT)
    {
        grainPressureMin_.value() = VGREAT;
        return lowest;
    }
    grainPressureMin_.value() = lowest;

    Info<< "Grain pressure seen by the rheology: min = " << lowest << " Pa";
    if (lowest < -tensionWarning_.value())
    {
        Info<< ": tension in the grains, below -tensionWarning "
            << tensionWarning_.value() << " Pa (" << dictName_
            << "); the rheology sees p_min there";
    }
    Info<< endl;
    return lowest;
}


void Foam::granularPressure::read(const dictionary& dict)
{
    tensionWarning_ = readTensionWarning(dict);
}


// ************************************************************************* //
