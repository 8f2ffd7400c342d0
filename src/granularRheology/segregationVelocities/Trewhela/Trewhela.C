/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "Trewhela.H"
#include "granularInput.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace segregationVelocities
{
    defineTypeNameAndDebug(Trewhela, 0);
    addToRunTimeSelectionTable(segregationVelocity, Trewhela, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::segregationVelocities::Trewhela::Trewhela
(
    const dictionary& dict,
    const granularRheology& rheology,
    const label a,
    const label b
)
:
    segregationVelocity(dict, rheology, a, b)
{
    const dictionary& coeffs = granularInput::coeffsDict(dict, typeName);

    // Defaults: table 2
    B_ = granularInput::readNonNegativeOrDefault(coeffs, "B", dimless, 0.3744).value();
    C_ = granularInput::readNonNegativeOrDefault(coeffs, "C", dimless, 0.2712).value();
    E_ = granularInput::readNonNegativeOrDefault(coeffs, "E", dimless, 2.0957).value();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::segregationVelocities::Trewhela::f
(
    const granularState& state,
    scalarField& result
) const
{
    const scalar rg = rheology_.rhoStar().value()*state.g;
    const scalar Rm1 = R() - 1;
    const scalarField& wl = state.w[large_];
    const scalarField& ws = state.w[small_];

    forAll(result, i)
    {
        const scalar wPair = wl[i] + ws[i];
        const scalar phil = (wPair > ROOTVSMALL ? wl[i]/wPair : 0.5);
        const scalar dbar = state.dbar[i];

        // (3.9), with gammaDot = 2|D| as in (6.8a)
        result[i] =
            B_*rg*state.shearRate[i]*sqr(dbar)/(C_*rg*dbar + state.p[i])
           *(Rm1 + E_*phil*sqr(Rm1));
    }
}


// ************************************************************************* //
