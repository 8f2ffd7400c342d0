/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularPrghPressureFvPatchScalarField.H"
#include "addToRunTimeSelectionTable.H"
#include "volFields.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularPrghPressureFvPatchScalarField::
granularPrghPressureFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF
)
:
    fixedValueFvPatchScalarField(p, iF),
    rhoName_("rho"),
    ghName_("gh"),
    p_(p.size(), Zero)
{}


Foam::granularPrghPressureFvPatchScalarField::
granularPrghPressureFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const dictionary& dict
)
:
    fixedValueFvPatchScalarField(p, iF, dict, false),
    rhoName_(dict.getOrDefault<word>("rho", "rho")),
    ghName_(dict.getOrDefault<word>("gh", "gh")),
    p_("p", dict, p.size())
{
    fvPatchScalarField::operator=
    (
        dict.found("value")
      ? scalarField("value", dict, p.size())
      : p_
    );
}


Foam::granularPrghPressureFvPatchScalarField::
granularPrghPressureFvPatchScalarField
(
    const granularPrghPressureFvPatchScalarField& ptf,
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    fixedValueFvPatchScalarField(ptf, p, iF, mapper),
    rhoName_(ptf.rhoName_),
    ghName_(ptf.ghName_),
    p_(ptf.p_, mapper)
{}


Foam::granularPrghPressureFvPatchScalarField::
granularPrghPressureFvPatchScalarField
(
    const granularPrghPressureFvPatchScalarField& ptf
)
:
    fixedValueFvPatchScalarField(ptf),
    rhoName_(ptf.rhoName_),
    ghName_(ptf.ghName_),
    p_(ptf.p_)
{}


Foam::granularPrghPressureFvPatchScalarField::
granularPrghPressureFvPatchScalarField
(
    const granularPrghPressureFvPatchScalarField& ptf,
    const DimensionedField<scalar, volMesh>& iF
)
:
    fixedValueFvPatchScalarField(ptf, iF),
    rhoName_(ptf.rhoName_),
    ghName_(ptf.ghName_),
    p_(ptf.p_)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::granularPrghPressureFvPatchScalarField::autoMap
(
    const fvPatchFieldMapper& m
)
{
    fixedValueFvPatchScalarField::autoMap(m);
    p_.autoMap(m);
}


void Foam::granularPrghPressureFvPatchScalarField::rmap
(
    const fvPatchScalarField& ptf,
    const labelList& addr
)
{
    fixedValueFvPatchScalarField::rmap(ptf, addr);
    p_.rmap
    (
        refCast<const granularPrghPressureFvPatchScalarField>(ptf).p_,
        addr
    );
}


void Foam::granularPrghPressureFvPatchScalarField::updateCoeffs()
{
    if (updated())
    {
        return;
    }

    const fvPatchScalarField& rhop =
        patch().lookupPatchField<volScalarField, scalar>(rhoName_);
    const fvPatchScalarField& ghp =
        patch().lookupPatchField<volScalarField, scalar>(ghName_);

    operator==(p_ - rhop*ghp);

    fixedValueFvPatchScalarField::updateCoeffs();
}


void Foam::granularPrghPressureFvPatchScalarField::write(Ostream& os) const
{
    fvPatchScalarField::write(os);
    os.writeEntryIfDifferent<word>("rho", "rho", rhoName_);
    os.writeEntryIfDifferent<word>("gh", "gh", ghName_);
    p_.writeEntry("p", os);
    writeEntry("value", os);
}


// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
    makePatchTypeField
    (
        fvPatchScalarField,
        granularPrghPressureFvPatchScalarField
    );
}


// ************************************************************************* //
