/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "constantSegregationVelocity.H"
#include "surfaceInterpolate.H"
#include "granularInput.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace segregationVelocities
{
    defineTypeNameAndDebug(constant, 0);
    addToRunTimeSelectionTable(segregationVelocity, constant, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::segregationVelocities::constant::constant
(
    const dictionary& dict,
    const granularRheology& rheology,
    const label a,
    const label b
)
:
    segregationVelocity(dict, rheology, a, b),
    value_
    (
        granularInput::readNonNegative
        (
            granularInput::coeffsDict(dict, typeName), "f", dimVelocity
        ).value()
    )
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::surfaceScalarField>
Foam::segregationVelocities::constant::faceValues
(
    const volScalarField& f,
    const volScalarField&
) const
{
    return fvc::interpolate(f);
}


// ************************************************************************* //
