/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularAir.H"
#include "granularGravity.H"
#include "granularInput.H"
#include "fvcGrad.H"
#include "surfaceInterpolate.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

const Foam::Enum<Foam::granularAir::sharpening>
Foam::granularAir::sharpeningNames
({
    { sharpening::segregation, "segregation" },
    { sharpening::counterGradient, "counterGradient" },
    { sharpening::none, "none" },
});


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

void Foam::granularAir::readAir
(
    const dictionary& mixtureDict,
    const granularGravity& gravity
)
{
    const dictionary& dict = granularInput::subDict
    (
        mixtureDict, "air", "name, rho, eta and the sharpening of the air"
    );

    name_ = dict.getOrDefault<word>("name", "air");
    rho_ = granularInput::readPositive(dict, "rho", dimDensity);
    eta_ = granularInput::readPositive(dict, "eta", dimPressure*dimTime);
    sharpening_ =
        granularInput::readEnum
        (
            dict, "sharpening",
            sharpeningNames, sharpening::segregation
        );

    f_ = dimensionedScalar(dimVelocity, Zero);
    e_ = Zero;
    cAlpha_ = 0;

    if (sharpening_ == sharpening::segregation)
    {
        f_ = granularInput::readNonNegative(dict, "f", dimVelocity);

        vector e(Zero);
        const word d
        (
            granularInput::readVectorOrWord
            (
                dict, "direction", {"gravity", "antiGravity"}, e
            )
        );
        if (d == "gravity")
        {
            e_ = gravity.unit();
        }
        else if (d == "antiGravity")
        {
            e_ = -gravity.unit();
        }
        else if (mag(e) < SMALL)
        {
            FatalIOErrorInFunction(dict)
                << "Invalid value of keyword 'direction' in dictionary "
                << dict.name() << ": direction = " << e
                << " (a vector of nonzero length)" << nl
                << exit(FatalIOError);
        }
        else
        {
            e_ = e/mag(e);
        }
        if (f_.value() > 0 && mag(e_) < SMALL)
        {
            FatalIOErrorInFunction(dict)
                << "Invalid value of keyword 'direction' in dictionary "
                << dict.name() << ": direction = " << d
                << " but g = " << gravity.g().value() << " is zero" << nl
                << exit(FatalIOError);
        }
    }
    else if (sharpening_ == sharpening::counterGradient)
    {
        cAlpha_ = granularInput::readNonNegative(dict, "cAlpha").value();
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularAir::granularAir
(
    const dictionary& dict,
    const granularGravity& gravity
)
:
    name_(),
    rho_(dimDensity, Zero),
    eta_(dimPressure*dimTime, Zero),
    sharpening_(sharpening::segregation),
    f_(dimVelocity, Zero),
    e_(Zero),
    cAlpha_(0)
{
    readAir(dict, gravity);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::granularAir::relativeFluxes
(
    const PtrList<volScalarField>& alphas,
    const surfaceScalarField& phi,
    List<labelPair>& pairs,
    PtrList<surfaceScalarField>& phirs
) const
{
    const fvMesh& mesh = phi.mesh();

    if (sharpening_ == sharpening::segregation && f_.value() > 0)
    {
        // (4.5)
        const surfaceScalarField phirAir(f_*(e_ & mesh.Sf()));
        for (label i = 1; i < alphas.size(); ++i)
        {
            pairs.append(labelPair(0, i));
            phirs.append(new surfaceScalarField(phirAir));
        }
    }
    else if (sharpening_ == sharpening::counterGradient && cAlpha_ > 0)
    {
        // (4.9), as multiphaseInterFoam's compression
        surfaceScalarField phic(mag(phi/mesh.magSf()));
        phic = min(cAlpha_*phic, max(phic));

        const dimensionedScalar deltaN
        (
            "deltaN",
            1e-8/pow(average(mesh.V()), 1.0/3.0)
        );

        const volScalarField& a = alphas[0];
        for (label i = 1; i < alphas.size(); ++i)
        {
            const volScalarField& b = alphas[i];
            surfaceVectorField gradf
            (
                fvc::interpolate(b)*fvc::interpolate(fvc::grad(a))
              - fvc::interpolate(a)*fvc::interpolate(fvc::grad(b))
            );
            pairs.append(labelPair(0, i));
            phirs.append
            (
                new surfaceScalarField
                (
                    phic*((gradf/(mag(gradf) + deltaN)) & mesh.Sf())
                )
            );
        }
    }
}


void Foam::granularAir::read
(
    const dictionary& dict,
    const granularGravity& gravity
)
{
    const word oldName(name_);
    readAir(dict, gravity);
    if (name_ != oldName)
    {
        const dictionary& airDict = dict.subDict("air");
        FatalIOErrorInFunction(airDict)
            << "Invalid value of keyword 'name' in dictionary "
            << airDict.name() << ": name = " << name_ << " changed"
            << " during the run (it was " << oldName << "): the phase"
            << " fields are read at the start only; stop the run and"
            << " start it again" << nl
            << exit(FatalIOError);
    }
}


// ************************************************************************* //
