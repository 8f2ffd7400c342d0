/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "grainPairModel.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::grainPairModel::grainPairModel
(
    const dictionary& dict,
    const granularRheology& rheology,
    const label a,
    const label b
)
:
    dict_(dict),
    rheology_(rheology),
    small_(rheology.d(a) <= rheology.d(b) ? a : b),
    large_(rheology.d(a) <= rheology.d(b) ? b : a)
{}


// ************************************************************************* //
