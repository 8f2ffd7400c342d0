/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "UtterBehringer.H"
#include "granularInput.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace diffusivities
{
    defineTypeNameAndDebug(UtterBehringer, 0);
    addToRunTimeSelectionTable(diffusivity, UtterBehringer, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::diffusivities::UtterBehringer::UtterBehringer
(
    const dictionary& dict,
    const granularRheology& rheology,
    const label a,
    const label b
)
:
    diffusivity(dict, rheology, a, b),
    A_
    (
        granularInput::readNonNegativeOrDefault
        (
            granularInput::coeffsDict(dict, typeName), "A", dimless, 0.108
        ).value()   // default: table 2
    )
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::diffusivities::UtterBehringer::D
(
    const granularState& state,
    scalarField& result
) const
{
    // (3.7), with gammaDot = 2|D| as in (6.8b)
    result = A_*state.shearRate*sqr(state.dbar);
}


// ************************************************************************* //
