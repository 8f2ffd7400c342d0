/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularGravity.H"
#include "gravityMeshObject.H"
#include "cyclicPolyPatch.H"
#include "processorCyclicPolyPatch.H"
#include "surfaceInterpolate.H"

// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

Foam::vector Foam::granularGravity::bodyForce(const dictionary& dict) const
{
    const List<vector> listed
    (
        dict.getOrDefault<List<vector>>("bodyForceDirections", List<vector>())
    );
    for (const vector& d : listed)
    {
        if (mag(d) < SMALL)
        {
            FatalIOErrorInFunction(dict)
                << "Invalid value of keyword 'bodyForceDirections' in "
                << "dictionary " << dict.name() << ": " << listed
                << " (a direction of zero length)" << nl
                << exit(FatalIOError);
        }
    }

    // Orthonormal basis of the separation vectors of the cyclic patches
    // and of the listed directions
    List<vector> basis;
    auto add = [&basis](vector s)
    {
        for (const vector& b : basis)
        {
            s -= (s & b)*b;
        }
        if (mag(s) > SMALL)
        {
            basis.append(s/mag(s));
        }
    };
    for (const polyPatch& pp : mesh_.boundaryMesh())
    {
        const auto* cpp = isA<cyclicPolyPatch>(pp);
        vector s(Zero);
        if (cpp && !isA<processorCyclicPolyPatch>(pp))
        {
            if (cpp->size() && cpp->separated())
            {
                s = cpp->separation()[0];
            }
        }
        reduce(s, maxMagSqrOp<vector>());
        add(s);
    }
    for (const vector& d : listed)
    {
        add(d);
    }

    vector gb(Zero);
    for (const vector& b : basis)
    {
        gb += (g_.value() & b)*b;
    }
    return gb;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularGravity::granularGravity
(
    const fvMesh& mesh,
    const dictionary& dict
)
:
    mesh_(mesh),
    g_(meshObjects::gravity::New(mesh.time())),
    gBody_(bodyForce(dict))
{
    if (mag(gBody_) > 0)
    {
        Info<< "Gravity along the cyclic directions and bodyForceDirections "
            << gBody_
            << " acts as a body force; gh uses " << hydrostatic().value()
            << nl << endl;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::vector Foam::granularGravity::unit() const
{
    const scalar magg = mag(g_.value());
    return magg > SMALL ? g_.value()/magg : vector::zero;
}


Foam::dimensionedVector Foam::granularGravity::hydrostatic() const
{
    return dimensionedVector("g", g_.dimensions(), g_.value() - gBody_);
}


Foam::tmp<Foam::surfaceScalarField> Foam::granularGravity::faceForce
(
    const volScalarField& rho
) const
{
    return
        fvc::interpolate(rho)
       *(dimensionedVector("gb", g_.dimensions(), gBody_) & mesh_.Sf())
       /mesh_.magSf();
}


// ************************************************************************* //
