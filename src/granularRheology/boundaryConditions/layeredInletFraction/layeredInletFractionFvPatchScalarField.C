/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "layeredInletFractionFvPatchScalarField.H"
#include "addToRunTimeSelectionTable.H"
#include "surfaceFields.H"
#include "granularInput.H"

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


Foam::tmp<Foam::scalarField>
Foam::layeredInletFractionFvPatchScalarField::profile() const
{
    const scalarField fBelow(plane_.fractionBelow(patch(), h_));
    return fBelow*below_ + (1 - fBelow)*above_;
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
    plane_()
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
    below_(readFraction(dict, "below")),
    above_(readFraction(dict, "above")),
    plane_(dict)
{
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
    plane_(ptf.plane_)
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
    plane_(ptf.plane_)
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
    plane_(ptf.plane_)
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
    os.writeEntry("below", below_);
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
