/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "Jop.H"
#include "granularInput.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace frictionLaws
{
    defineTypeNameAndDebug(Jop, 0);
    addToRunTimeSelectionTable(frictionLaw, Jop, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::frictionLaws::Jop::Jop(const dictionary& dict)
:
    frictionLawCoeffs<Jop, 3>(dict)
{
    const dictionary& coeffs = granularInput::coeffsDict(dict, typeName);

    c_[MUS] = granularInput::readNonNegative(coeffs, "mus").value();
    c_[MUD] = granularInput::readNonNegative(coeffs, "mud").value();
    c_[I0] = granularInput::readPositive(coeffs, "I0").value();

    if (c_[MUS] >= c_[MUD])
    {
        granularInput::invalid
        (
            coeffs, "mus", c_[MUS],
            "must be < mud = " + Foam::name(c_[MUD])
          + "; for mu independent of I use frictionLaw constant"
        );
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::frictionLaws::Jop::inverse(const scalar muValue) const
{
    if (muValue < c_[MUS] || muValue >= c_[MUD])
    {
        FatalErrorInFunction
            << "mu = " << muValue << " is outside [mu_s, mu_d) = ["
            << c_[MUS] << ", " << c_[MUD] << ") of " << dict_.name()
            << ": no inertial number gives it"
            << exit(FatalError);
    }

    return inverseOf(muValue, c_[MUS], c_[MUD], c_[I0]);
}


// ************************************************************************* //
