/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "faceReconstruction.H"
#include "fvcSurfaceIntegrate.H"
#include "extrapolatedCalculatedFvPatchFields.H"

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::faceReconstruction::calcGeometry()
{
    SfHat_.reset(new surfaceVectorField("SfHat", mesh_.Sf()/mesh_.magSf()));
    invT_.reset
    (
        new volTensorField
        (
            "invSfHatSf",
            inv(fvc::surfaceSum(SfHat_()*mesh_.Sf()))
        )
    );
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::faceReconstruction::faceReconstruction(const fvMesh& mesh)
:
    mesh_(mesh)
{
    calcGeometry();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::faceReconstruction::update()
{
    if (mesh_.changing())
    {
        calcGeometry();
    }
}


Foam::tmp<Foam::volVectorField> Foam::faceReconstruction::operator()
(
    const surfaceScalarField& ssf
) const
{
    tmp<volVectorField> tU
    (
        new volVectorField
        (
            IOobject
            (
                "volIntegrate(" + ssf.name() + ')',
                ssf.instance(),
                mesh_,
                IOobject::NO_READ,
                IOobject::NO_WRITE
            ),
            invT_() & fvc::surfaceSum(SfHat_()*ssf),
            extrapolatedCalculatedFvPatchField<vector>::typeName
        )
    );

    tU.ref().correctBoundaryConditions();

    return tU;
}


Foam::tmp<Foam::volVectorField> Foam::faceReconstruction::operator()
(
    const tmp<surfaceScalarField>& tssf
) const
{
    tmp<volVectorField> tU(operator()(tssf()));
    tssf.clear();
    return tU;
}


// ************************************************************************* //
