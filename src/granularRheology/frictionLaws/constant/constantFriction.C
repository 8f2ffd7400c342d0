/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "constantFriction.H"
#include "granularInput.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace frictionLaws
{
    defineTypeNameAndDebug(constant, 0);
    addToRunTimeSelectionTable(frictionLaw, constant, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::frictionLaws::constant::constant(const dictionary& dict)
:
    frictionLawCoeffs<constant, 1>(dict)
{
    const dictionary& coeffs = granularInput::coeffsDict(dict, typeName);
    c_[0] = granularInput::readNonNegative(coeffs, "mu").value();
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::frictionLaws::constant::inverse(const scalar muValue) const
{
    FatalErrorInFunction
        << "Constant friction mu = " << c_[0] << " (" << dict_.name()
        << ") has no inverse I(mu = " << muValue << "): there is no "
        << "steady uniform (Bagnold) flow for a constant friction law"
        << exit(FatalError);
    return 0;
}


// ************************************************************************* //
