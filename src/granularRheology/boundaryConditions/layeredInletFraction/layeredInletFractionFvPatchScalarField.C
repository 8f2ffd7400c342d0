/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "layeredInletFractionFvPatchScalarField.H"
#include "addToRunTimeSelectionTable.H"
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
    fixedValueFvPatchScalarField(p, iF),
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
    fixedValueFvPatchScalarField(p, iF, dict, false),
    h_(granularInput::readPositive(dict, "h", dimLength).value()),
    below_(readFraction(dict, "below")),
    above_(readFraction(dict, "above")),
    plane_(dict)
{
    fvPatchScalarField::operator==(profile());
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
    fixedValueFvPatchScalarField(ptf, p, iF, mapper),
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
    fixedValueFvPatchScalarField(ptf),
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
    fixedValueFvPatchScalarField(ptf, iF),
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

    fvPatchScalarField::operator==(profile());

    fixedValueFvPatchScalarField::updateCoeffs();
}


void Foam::layeredInletFractionFvPatchScalarField::write(Ostream& os) const
{
    fvPatchScalarField::write(os);
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
