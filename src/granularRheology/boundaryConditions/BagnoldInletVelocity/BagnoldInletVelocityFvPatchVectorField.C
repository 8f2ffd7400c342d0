/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "BagnoldInletVelocityFvPatchVectorField.H"
#include "addToRunTimeSelectionTable.H"
#include "gravityMeshObject.H"
#include "granularInput.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::BagnoldInletVelocityFvPatchVectorField::
BagnoldInletVelocityFvPatchVectorField
(
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF
)
:
    fixedValueFvPatchVectorField(p, iF),
    h_(0),
    phase_(),
    plane_(),
    Lz_(0),
    depthAveragedFrame_(false),
    frameVelocity_(Zero)
{}


Foam::BagnoldInletVelocityFvPatchVectorField::
BagnoldInletVelocityFvPatchVectorField
(
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF,
    const dictionary& dict
)
:
    fixedValueFvPatchVectorField(p, iF, dict, false),
    h_(granularInput::readPositive(dict, "h", dimLength).value()),
    phase_(dict.getOrDefault<word>("phase", word::null)),
    plane_(dict),
    Lz_(0),
    depthAveragedFrame_(false),
    frameVelocity_(Zero)
{
    if (dict.found("frameVelocity"))
    {
        depthAveragedFrame_ =
            granularInput::readVectorOrWord
            (
                dict, "frameVelocity", {"depthAveraged"}, frameVelocity_
            ) == "depthAveraged";
    }

    // The rheology and air of constant/granularProperties
    const dictionary props(granularInput::readProperties(db()));
    if (!props.isDict("air"))
    {
        FatalIOErrorInFunction(props)
            << "Missing sub-dictionary 'air' in " << props.name()
            << " (its rho and eta set the air inflow profile (5.7))" << nl
            << exit(FatalIOError);
    }
    const dictionary& air = props.subDict("air");

    // L_z: the top of the patch, found once over all processors and written
    // back, so that tools that read one processor at a time (reconstructPar)
    // see the same profile; a patch without faces anywhere has no air
    if (!dict.readIfPresent("Lz", Lz_))
    {
        Lz_ =
            returnReduce(p.size(), sumOp<label>())
          ? plane_.top(p)
          : h_;
    }
    const granularRheology rheology(props);

    flow_.reset
    (
        new BagnoldFlow
        (
            rheology,
            phase_.empty() ? rheology.names()[0] : phase_,
            meshObjects::gravity::New(db().time()).value(),
            plane_.normal(),
            h_,
            Lz_,
            granularInput::readPositive(air, "rho", dimDensity).value(),
            granularInput::readPositive(air, "eta", dimPressure*dimTime)
               .value(),
            dict
        )
    );

    fvPatchVectorField::operator==(profile());
}


Foam::BagnoldInletVelocityFvPatchVectorField::
BagnoldInletVelocityFvPatchVectorField
(
    const BagnoldInletVelocityFvPatchVectorField& ptf,
    const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    fixedValueFvPatchVectorField(ptf, p, iF, mapper),
    h_(ptf.h_),
    phase_(ptf.phase_),
    plane_(ptf.plane_),
    Lz_(ptf.Lz_),
    depthAveragedFrame_(ptf.depthAveragedFrame_),
    frameVelocity_(ptf.frameVelocity_),
    flow_(ptf.flow_.valid() ? new BagnoldFlow(*ptf.flow_) : nullptr)
{}


Foam::BagnoldInletVelocityFvPatchVectorField::
BagnoldInletVelocityFvPatchVectorField
(
    const BagnoldInletVelocityFvPatchVectorField& ptf
)
:
    fixedValueFvPatchVectorField(ptf),
    h_(ptf.h_),
    phase_(ptf.phase_),
    plane_(ptf.plane_),
    Lz_(ptf.Lz_),
    depthAveragedFrame_(ptf.depthAveragedFrame_),
    frameVelocity_(ptf.frameVelocity_),
    flow_(ptf.flow_.valid() ? new BagnoldFlow(*ptf.flow_) : nullptr)
{}


Foam::BagnoldInletVelocityFvPatchVectorField::
BagnoldInletVelocityFvPatchVectorField
(
    const BagnoldInletVelocityFvPatchVectorField& ptf,
    const DimensionedField<vector, volMesh>& iF
)
:
    fixedValueFvPatchVectorField(ptf, iF),
    h_(ptf.h_),
    phase_(ptf.phase_),
    plane_(ptf.plane_),
    Lz_(ptf.Lz_),
    depthAveragedFrame_(ptf.depthAveragedFrame_),
    frameVelocity_(ptf.frameVelocity_),
    flow_(ptf.flow_.valid() ? new BagnoldFlow(*ptf.flow_) : nullptr)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

const Foam::BagnoldFlow&
Foam::BagnoldInletVelocityFvPatchVectorField::flow() const
{
    if (!flow_.valid())
    {
        FatalErrorInFunction
            << "Patch " << patch().name() << " of " << internalField().name()
            << " was not constructed from a dictionary: no inflow profile"
            << exit(FatalError);
    }
    return *flow_;
}


Foam::vector
Foam::BagnoldInletVelocityFvPatchVectorField::frameVelocity() const
{
    return
        depthAveragedFrame_
      ? flow().ubar()*flow().downslope()
      : frameVelocity_;
}


void Foam::BagnoldInletVelocityFvPatchVectorField::setFrameVelocity
(
    const vector& U
)
{
    depthAveragedFrame_ = false;
    frameVelocity_ = U;
    fvPatchVectorField::operator==(profile());
}


Foam::tmp<Foam::vectorField>
Foam::BagnoldInletVelocityFvPatchVectorField::profile() const
{
    const BagnoldFlow& f = flow();
    const scalarField z(plane_.faceHeight(patch()));
    const vector Uframe(frameVelocity());

    tmp<vectorField> tU(new vectorField(z.size()));
    vectorField& U = tU.ref();
    forAll(z, facei)
    {
        U[facei] = f.u(z[facei])*f.downslope() - Uframe;
    }
    return tU;
}


void Foam::BagnoldInletVelocityFvPatchVectorField::updateCoeffs()
{
    if (updated())
    {
        return;
    }

    fvPatchVectorField::operator==(profile());

    fixedValueFvPatchVectorField::updateCoeffs();
}


void Foam::BagnoldInletVelocityFvPatchVectorField::write(Ostream& os) const
{
    fvPatchVectorField::write(os);
    os.writeEntry("h", h_);
    if (!phase_.empty())
    {
        os.writeEntry("phase", phase_);
    }
    plane_.write(os);
    os.writeEntry("Lz", Lz_);
    if (depthAveragedFrame_)
    {
        os.writeEntry("frameVelocity", word("depthAveraged"));
    }
    else if (mag(frameVelocity_) > 0)
    {
        os.writeEntry("frameVelocity", frameVelocity_);
    }
    writeEntry("value", os);
}


// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
    makePatchTypeField
    (
        fvPatchVectorField,
        BagnoldInletVelocityFvPatchVectorField
    );
}


// ************************************************************************* //
