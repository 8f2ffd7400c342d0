/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "hydrostaticOutletPressureFvPatchScalarField.H"
#include "addToRunTimeSelectionTable.H"
#include "volFields.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::hydrostaticOutletPressureFvPatchScalarField::
hydrostaticOutletPressureFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF
)
:
    fixedGradientFvPatchScalarField(p, iF),
    rhoName_("rho"),
    ghName_("gh")
{}


Foam::hydrostaticOutletPressureFvPatchScalarField::
hydrostaticOutletPressureFvPatchScalarField
(
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const dictionary& dict
)
:
    fixedGradientFvPatchScalarField(p, iF),
    rhoName_(dict.getOrDefault<word>("rho", "rho")),
    ghName_(dict.getOrDefault<word>("gh", "gh"))
{
    gradient() = Zero;
    fvPatchScalarField::operator=
    (
        dict.found("value")
      ? scalarField("value", dict, p.size())
      : patchInternalField()()
    );
}


Foam::hydrostaticOutletPressureFvPatchScalarField::
hydrostaticOutletPressureFvPatchScalarField
(
    const hydrostaticOutletPressureFvPatchScalarField& ptf,
    const fvPatch& p,
    const DimensionedField<scalar, volMesh>& iF,
    const fvPatchFieldMapper& mapper
)
:
    fixedGradientFvPatchScalarField(ptf, p, iF, mapper),
    rhoName_(ptf.rhoName_),
    ghName_(ptf.ghName_)
{}


Foam::hydrostaticOutletPressureFvPatchScalarField::
hydrostaticOutletPressureFvPatchScalarField
(
    const hydrostaticOutletPressureFvPatchScalarField& ptf
)
:
    fixedGradientFvPatchScalarField(ptf),
    rhoName_(ptf.rhoName_),
    ghName_(ptf.ghName_)
{}


Foam::hydrostaticOutletPressureFvPatchScalarField::
hydrostaticOutletPressureFvPatchScalarField
(
    const hydrostaticOutletPressureFvPatchScalarField& ptf,
    const DimensionedField<scalar, volMesh>& iF
)
:
    fixedGradientFvPatchScalarField(ptf, iF),
    rhoName_(ptf.rhoName_),
    ghName_(ptf.ghName_)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::hydrostaticOutletPressureFvPatchScalarField::updateCoeffs()
{
    if (updated())
    {
        return;
    }

    const fvPatchScalarField& rhop =
        patch().lookupPatchField<volScalarField, scalar>(rhoName_);
    const fvPatchScalarField& ghp =
        patch().lookupPatchField<volScalarField, scalar>(ghName_);

    // dp/dn = 0 with p = p_rgh + rho gh and drho/dn = 0; gh is linear, so
    // its normal gradient on the patch is that of the solver's gh
    gradient() = -rhop*ghp.snGrad();

    fixedGradientFvPatchScalarField::updateCoeffs();
}


void Foam::hydrostaticOutletPressureFvPatchScalarField::write
(
    Ostream& os
) const
{
    fvPatchScalarField::write(os);
    os.writeEntryIfDifferent<word>("rho", "rho", rhoName_);
    os.writeEntryIfDifferent<word>("gh", "gh", ghName_);
    writeEntry("value", os);
}


// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace Foam
{
    makePatchTypeField
    (
        fvPatchScalarField,
        hydrostaticOutletPressureFvPatchScalarField
    );
}


// ************************************************************************* //
