/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "BarkerGray.H"
#include "Jop.H"
#include "granularInput.H"
#include "wellPosedness.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace frictionLaws
{
    defineTypeNameAndDebug(BarkerGray, 0);
    addToRunTimeSelectionTable(frictionLaw, BarkerGray, dictionary);
}
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::frictionLaws::BarkerGray::BarkerGray(const dictionary& dict)
:
    frictionLawCoeffs<BarkerGray, 6>(dict)
{
    const dictionary& coeffs = granularInput::coeffsDict(dict, typeName);

    c_[MUS] = granularInput::readNonNegative(coeffs, "mus").value();
    c_[MUD] = granularInput::readNonNegative(coeffs, "mud").value();
    c_[MUINF] = granularInput::readNonNegative(coeffs, "muInf").value();
    c_[I0] = granularInput::readPositive(coeffs, "I0").value();
    c_[ALPHA] = granularInput::readPositive(coeffs, "alpha").value();
    c_[I1] = granularInput::readPositive(coeffs, "I1").value();

    if (c_[MUS] >= c_[MUD])
    {
        granularInput::invalid
        (
            coeffs, "mus", c_[MUS], "must be < mud = " + Foam::name(c_[MUD])
        );
    }

    // I_1 is meant to lie in the well-posed range of the high branch; a
    // warning (not an error: the law is still defined) when it does not
    const scalar I1plus = c_[I1]*(1 + 1e-9);
    if (wellPosedness::illPosed(muOf(I1plus, c_), I1plus*dmudIOf(I1plus, c_)))
    {
        WarningInFunction
            << "I1 = " << c_[I1] << " in " << coeffs.name()
            << " lies where the high branch of (2.8) is ill posed by (2.6);"
            << " choose I1 at the lower bound of the well-posed range of the"
            << " Jop law with the same mus, mud, I0 (granularWellPosedness"
            << " prints it)" << endl;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::frictionLaws::BarkerGray::inverse
(
    const scalar muValue
) const
{
    if (muValue <= 0)
    {
        return 0;
    }

    // Creep branch: invert mu^2 = alpha/log(A/I)
    if (muValue <= muHigh(c_[I1], c_))
    {
        return exp(logA(c_) - c_[ALPHA]/sqr(muValue));
    }

    if (c_[MUINF] > 0)
    {
        // (5.6): the positive root of
        // mu_inf I^2 + (mu_d - mu) I + (mu_s - mu) I_0 = 0
        return
            (
                muValue - c_[MUD]
              + sqrt
                (
                    sqr(c_[MUD] - muValue)
                  + 4*(muValue - c_[MUS])*c_[MUINF]*c_[I0]
                )
            )/(2*c_[MUINF]);
    }

    if (muValue >= c_[MUD])
    {
        FatalErrorInFunction
            << "mu = " << muValue << " >= mu_d = " << c_[MUD]
            << " with mu_inf = 0 in " << dict_.name()
            << ": no inertial number gives it"
            << exit(FatalError);
    }

    // mu_inf = 0: the high branch is (2.7)
    return Jop::inverseOf(muValue, c_[MUS], c_[MUD], c_[I0]);
}


// ************************************************************************* //
