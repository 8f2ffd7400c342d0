/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularSidewallFriction.H"
#include "granularInput.H"
#include "fvMatrices.H"
#include "fvmSup.H"
#include "volFields.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace fv
{
    defineTypeNameAndDebug(granularSidewallFriction, 0);
    addToRunTimeSelectionTable(option, granularSidewallFriction, dictionary);
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::fv::granularSidewallFriction::readCoeffs()
{
    muW_ = granularInput::readNonNegative(coeffs_, "muW");
    W_ = granularInput::readPositive(coeffs_, "W", dimLength);

    // 1e-6 m/s: far below the speeds of a flow (cm/s to m/s), so the
    // force is Coulomb's wherever the grains slide; a body held below
    // the Coulomb value creeps at most at u_small (10 um per 10 s turn of
    // a drum, well below a cell)
    uSmall_ = granularInput::readPositiveOrDefault
    (
        coeffs_, "uSmall", dimVelocity, 1e-6
    );

    pName_ = coeffs_.lookupOrDefault<word>("p", "pGranular");
    alphaAirName_ = coeffs_.lookupOrDefault<word>("alphaAir", "alpha.air");
    UName_ = coeffs_.lookupOrDefault<word>("U", "U");

    wallVelocity_ = Zero;
    rotation_.clear();
    if (coeffs_.found("wallVelocity"))
    {
        const word motion
        (
            granularInput::readVectorOrWord
            (
                coeffs_, "wallVelocity", {"rotation"}, wallVelocity_
            )
        );
        if (motion == "rotation")
        {
            rotation_.reset(new meshRotation(mesh_.time()));
        }
    }

    fieldNames_ = wordList(1, UName_);
    applied_.setSize(fieldNames_.size(), false);

    Info<< "    Sidewall friction (Jop et al. 2005): mu_w = " << muW_.value()
        << ", W = " << W_.value() << " m, u_small = " << uSmall_.value()
        << " m/s, p_g = " << pName_ << ", air = " << alphaAirName_
        << ", walls ";
    if (rotation_.valid())
    {
        Info<< "turning with the mesh" << endl;
    }
    else
    {
        Info<< "at " << wallVelocity_ << " m/s" << endl;
    }
}


Foam::tmp<Foam::volVectorField::Internal>
Foam::fv::granularSidewallFriction::wallVelocity() const
{
    tmp<volVectorField::Internal> tUw
    (
        new volVectorField::Internal
        (
            IOobject
            (
                name_ + ":wallVelocity",
                mesh_.time().timeName(),
                mesh_,
                IOobject::NO_READ,
                IOobject::NO_WRITE,
                false
            ),
            mesh_,
            dimensionedVector("wallVelocity", dimVelocity, wallVelocity_)
        )
    );
    if (rotation_.valid())
    {
        tUw.ref().field() =
            rotation_->velocity(mesh_.C().field(), mesh_.time().value());
    }
    return tUw;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::fv::granularSidewallFriction::granularSidewallFriction
(
    const word& name,
    const word& modelType,
    const dictionary& dict,
    const fvMesh& mesh
)
:
    cellSetOption(name, modelType, dict, mesh),
    muW_("muW", dimless, Zero),
    W_("W", dimLength, Zero),
    uSmall_("uSmall", dimVelocity, Zero),
    pName_(),
    alphaAirName_(),
    UName_(),
    wallVelocity_(Zero),
    rotation_()
{
    readCoeffs();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::volScalarField::Internal>
Foam::fv::granularSidewallFriction::K
(
    const volVectorField& U,
    const volVectorField::Internal& Uw
) const
{
    const volScalarField& pg = mesh_.lookupObject<volScalarField>(pName_);

    // (JFP): K = phi^g 2 mu_w p_g/(W max(|u - u_w|, u_small)); a negative
    // p_g (a drum's rising corner) gives no friction, never a push
    tmp<volScalarField::Internal> tK
    (
        2*muW_/W_
       *max(pg(), dimensionedScalar(dimPressure, Zero))
       /max(mag(U() - Uw), uSmall_)
    );
    volScalarField::Internal& K = tK.ref();

    if (alphaAirName_ != "none")
    {
        const volScalarField& alphaAir =
            mesh_.lookupObject<volScalarField>(alphaAirName_);
        K.field() *= max(min(1 - alphaAir.primitiveField(), 1.0), 0.0);
    }

    if (selectionMode() != smAll)
    {
        scalarField inSet(mesh_.nCells(), Zero);
        UIndirectList<scalar>(inSet, cells()) = 1;
        K.field() *= inSet;
    }

    return tK;
}


void Foam::fv::granularSidewallFriction::addSup
(
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    FatalErrorInFunction
        << type() << " " << name_ << ": the wall friction is a force per"
        << " unit volume; it needs the momentum equation in rho U form"
        << " (fvOptions(rho, U)), not " << eqn.psi().name() << "'s"
        << " kinematic form" << exit(FatalError);
}


void Foam::fv::granularSidewallFriction::addSup
(
    const volScalarField&,
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    const volVectorField& U = eqn.psi();
    const tmp<volVectorField::Internal> tUw(wallVelocity());
    const tmp<volScalarField::Internal> tK(K(U, tUw()));

    // The source -K (u - u_w): -K u on the diagonal, K u_w explicit
    eqn -= fvm::Sp(tK(), U);
    if (rotation_.valid() || wallVelocity_ != vector::zero)
    {
        eqn += tK()*tUw();
    }
}


bool Foam::fv::granularSidewallFriction::read(const dictionary& dict)
{
    if (cellSetOption::read(dict))
    {
        readCoeffs();
        return true;
    }
    return false;
}


// ************************************************************************* //
