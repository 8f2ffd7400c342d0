/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "constantDiffusivity.H"
#include "granularInput.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace diffusivities
{
    defineTypeNameAndDebug(constant, 0);
    addToRunTimeSelectionTable(diffusivity, constant, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::diffusivities::constant::constant
(
    const dictionary& dict,
    const granularRheology& rheology,
    const label a,
    const label b
)
:
    diffusivity(dict, rheology, a, b),
    value_
    (
        granularInput::readNonNegative
        (
            granularInput::coeffsDict(dict, typeName), "D", dimArea/dimTime
        ).value()
    )
{}


// ************************************************************************* //
