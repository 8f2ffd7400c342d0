/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "segregationVelocity.H"
#include "surfaceInterpolate.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
    defineTypeNameAndDebug(segregationVelocity, 0);
    defineRunTimeSelectionTable(segregationVelocity, dictionary);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::surfaceScalarField> Foam::segregationVelocity::faceValues
(
    const volScalarField& f,
    const volScalarField& aij
) const
{
    const surfaceScalarField aijf(fvc::interpolate(aij));
    return
        pos(aijf - SMALL)*fvc::interpolate(aij*f)
       /max(aijf, dimensionedScalar("small", dimless, SMALL))
      + neg0(aijf - SMALL)*fvc::interpolate(f);
}


// ************************************************************************* //
