/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "layeredInletFractionFvPatchScalarField.H"
#include "addToRunTimeSelectionTable.H"
#include "surfaceFields.H"
#include "granularInput.H"
#include "gravityMeshObject.H"

// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::scalar Foam::layeredInletFractionFvPatchScalarField::readFraction
(
    const dictionary& dict,
    const word& key
)
{
    const scalar value = dict.get<scalar>(key);
    if (!(value >= 0 && value <= 1))
    {
        granularInput::invalid(dict, key, value, "a fraction in [0, 1]");
    }
    return value;
}


void Foam::layeredInletFractionFvPatchScalarField::readBelow
(
    const dictionary& dict
)
{
    ITstream& is = dict.lookup("below");
    token t(is);
    if (!t.isWord())
    {
        below_ = readFraction(dict, "below");
        return;
    }
    if (t.wordToken() != "stratified")
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'below' in dictionary "
            << dict.name() << ": below = " << t.wordToken()
            << " (a fraction in [0, 1], or stratified)" << nl
            << exit(FatalIOError);
    }

    const granularRheology rheology(granularInput::readProperties(db()));
    phase_ = dict.getOrDefault<word>("phase", internalField().name().ext());
    grain_ = rheology.index(phase_);
    if (grain_ < 0)
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'phase' in dictionary "
            << dict.name() << ": phase = " << phase_ << " (below stratified"
            << " needs a grain phase of " << rheology.dict().name() << ": "
            << rheology.names() << ")" << nl << exit(FatalIOError);
    }

    const vector g(meshObjects::gravity::New(db().time()).value());
    const vector n(plane_.normal()/mag(plane_.normal()));
    composition_.reset
    (
        new GrayChugunov(rheology, h_, -(g & n)/max(mag(g), VSMALL), dict)
    );
}


Foam::tmp<Foam::scalarField>
Foam::layeredInletFractionFvPatchScalarField::profile() const
{
    const scalarField fBelow(plane_.fractionBelow(patch(), h_));
    if (!composition_.valid())
    {
        return fBelow*below_ + (1 - fBelow)*above_;
    }

    // (5.8) at the face centre, or at h for a face cut by z = h
    const scalarField z(plane_.faceHeight(patch()));
    tmp<scalarField> tf(new scalarField(z.size()));
    scalarField& f = tf.ref();
    forAll(f, facei)
    {
        f[facei] =
            fBelow[facei]*composition_->fraction(grain_, z[facei])
          + (1 - fBelow[facei])*above_;
    }
    return tf;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::layeredInletFractionFvPatchScalarField::
layeredInletFractionFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF
)
:
    inletOutletFvPatchScalarField(p, iF),
    h_(0),
    below_(0),
    above_(0),
    plane_(),
    composition_(),
    phase_(),
    grain_(-1)
{}


Foam::layeredInletFractionFvPatchScalarField::
layeredInletFractionFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const dictionary& dict
)
:
    inletOutletFvPatchScalarField(p, iF),
    h_(granularInput::readPositive(dict, "h", dimLength).value()),
    below_(0),
    above_(readFraction(dict, "above")),
    plane_(dict),
    composition_(),
    phase_(),
    grain_(-1)
{
    readBelow(dict);
    phiName_ = dict.getOrDefault<word>("phi", "phi");
    refValue() = profile();
    refGrad() = Zero;
    valueFraction() = 1;
    fvPatchScalarField::operator=
    (
        dict.found("value")
      ? scalarField("value", dict, p.size())
      : refValue()
    );
}


Foam::layeredInletFractionFvPatchScalarField::
layeredInletFractionFvPatchScalarField
(
    const layeredInletFractionFvPatchScalarField& ptf,
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    inletOutletFvPatchScalarField(ptf, p, iF, mapper),
    h_(ptf.h_),
    below_(ptf.below_),
    above_(ptf.above_),
    plane_(ptf.plane_),
    composition_
    (
        ptf.composition_.valid() ? new GrayChugunov(*ptf.composition_) : nullptr
    ),
    phase_(ptf.phase_),
    grain_(ptf.grain_)
{}


Foam::layeredInletFractionFvPatchScalarField::
layeredInletFractionFvPatchScalarField
(
    const layeredInletFractionFvPatchScalarField& ptf
)
:
    inletOutletFvPatchScalarField(ptf),
    h_(ptf.h_),
    below_(ptf.below_),
    above_(ptf.above_),
    plane_(ptf.plane_),
    composition_
    (
        ptf.composition_.valid() ? new GrayChugunov(*ptf.composition_) : nullptr
    ),
    phase_(ptf.phase_),
    grain_(ptf.grain_)
{}


Foam::layeredInletFractionFvPatchScalarField::
layeredInletFractionFvPatchScalarField
(
    const layeredInletFractionFvPatchScalarField& ptf,
    const DimensionedField<scalar, volMesh>& iF
)
:
    inletOutletFvPatchScalarField(ptf, iF),
    h_(ptf.h_),
    below_(ptf.below_),
    above_(ptf.above_),
    plane_(ptf.plane_),
    composition_
    (
        ptf.composition_.valid() ? new GrayChugunov(*ptf.composition_) : nullptr
    ),
    phase_(ptf.phase_),
    grain_(ptf.grain_)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::layeredInletFractionFvPatchScalarField::updateCoeffs()
{
    if (updated())
    {
        return;
    }

    refValue() = profile();

    inletOutletFvPatchScalarField::updateCoeffs();
}


void Foam::layeredInletFractionFvPatchScalarField::write(Ostream& os) const
{
    fvPatchScalarField::write(os);
    os.writeEntryIfDifferent<word>("phi", "phi", phiName_);
    os.writeEntry("h", h_);
    if (composition_.valid())
    {
        os.writeEntry("below", word("stratified"));
        os.writeEntry("phibar", composition_->phibar());
        os.writeEntry("phase", phase_);
    }
    else
    {
        os.writeEntry("below", below_);
    }
    os.writeEntry("above", above_);
    plane_.write(os);
    writeEntry("value", os);
}


// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
    makePatchTypeField
    (
        fvPatchScalarField,
        layeredInletFractionFvPatchScalarField
    );
}


// ************************************************************************* //
