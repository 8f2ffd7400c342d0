/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "inclinedPlane.H"
#include "polyMesh.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::inclinedPlane::inclinedPlane()
:
    origin_(Zero),
    normal_(0, 0, 1)
{}


Foam::inclinedPlane::inclinedPlane(const dictionary& dict)
:
    origin_(dict.getOrDefault<point>("origin", Zero)),
    normal_(dict.getOrDefault<vector>("normal", vector(0, 0, 1)))
{
    if (mag(normal_) < SMALL)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'normal' in dictionary "
            << dict.name() << ": normal = " << normal_
            << " (a vector of nonzero length)" << nl << exit(FatalIOError);
    }
    normal_ /= mag(normal_);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::scalarField>
Foam::inclinedPlane::height(const pointField& points) const
{
    return (points - origin_) & normal_;
}


Foam::tmp<Foam::scalarField>
Foam::inclinedPlane::faceHeight(const fvPatch& p) const
{
    return height(p.Cf());
}


Foam::tmp<Foam::scalarField>
Foam::inclinedPlane::fractionBelow(const fvPatch& p, const scalar h) const
{
    const polyPatch& pp = p.patch();
    const scalarField zPoints(height(pp.localPoints()));
    const scalarField zFaces(faceHeight(p));

    tmp<scalarField> tfraction(new scalarField(p.size()));
    scalarField& fraction = tfraction.ref();

    forAll(pp.localFaces(), facei)
    {
        const face& f = pp.localFaces()[facei];
        scalar zMin = GREAT;
        scalar zMax = -GREAT;
        forAll(f, pi)
        {
            zMin = min(zMin, zPoints[f[pi]]);
            zMax = max(zMax, zPoints[f[pi]]);
        }

        // A face parallel to the base is below or above as a whole
        fraction[facei] =
            zMax - zMin > SMALL*max(mag(zMax), scalar(1))
          ? min(max((h - zMin)/(zMax - zMin), scalar(0)), scalar(1))
          : scalar(zFaces[facei] <= h);
    }

    return tfraction;
}


Foam::scalar Foam::inclinedPlane::top(const fvPatch& p) const
{
    return gMax(height(p.patch().localPoints()));
}


void Foam::inclinedPlane::write(Ostream& os) const
{
    os.writeEntry("origin", origin_);
    os.writeEntry("normal", normal_);
}


// ************************************************************************* //
