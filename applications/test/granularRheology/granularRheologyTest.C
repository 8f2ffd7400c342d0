/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularRheologyTest.H"
#include "IStringStream.H"
#include "segregationVelocity.H"
#include "diffusivity.H"
#include "wellPosedness.H"
#include "mathematicalConstants.H"

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

namespace
{
    Foam::label nPassed_ = 0;
    Foam::label nFailed_ = 0;
}


Foam::label Foam::granularRheologyTest::nPassed()
{
    return nPassed_;
}


Foam::label Foam::granularRheologyTest::nFailed()
{
    return nFailed_;
}


namespace Foam
{
namespace granularRheologyTest
{

void check(const std::string& name, const bool ok, const std::string& detail)
{
    if (ok)
    {
        ++nPassed_;
        Info<< "PASS " << name.c_str() << nl;
    }
    else
    {
        ++nFailed_;
        Info<< "FAIL " << name.c_str() << ": " << detail.c_str() << nl;
    }
}

void checkClose
(
    const std::string& name,
    const scalar actual,
    const scalar expected,
    const scalar relTol
)
{
    const scalar err = mag(actual - expected)/max(mag(expected), VSMALL);
    std::ostringstream os;
    os.precision(12);
    os << "got " << actual << ", expected " << expected
       << ", relative error " << err << " > " << relTol;
    check(name, std::isfinite(actual) && err <= relTol, os.str());
}

dictionary parse(const std::string& text)
{
    IStringStream is(text);
    return dictionary(is);
}

void expectError
(
    const std::string& name,
    const std::function<void()>& f,
    const wordList& mustContain
)
{
    FatalError.throwExceptions();
    FatalIOError.throwExceptions();
    std::string detail;
    bool ok = false;
    try
    {
        f();
        detail = "no error raised";
    }
    catch (const Foam::error& err)
    {
        const string msg(err.message());
        ok = true;
        for (const word& w : mustContain)
        {
            if (msg.find(w) == string::npos)
            {
                ok = false;
                detail += "message lacks '" + w + "'; ";
            }
        }
        if (!ok)
        {
            detail += "message: " + msg;
        }
    }
    FatalError.dontThrowExceptions();
    FatalIOError.dontThrowExceptions();
    check(name, ok, detail);
}

const scalar deg = constant::mathematical::pi/180;

// Table 1
const std::string table1Jop =
    "frictionLaw Jop; JopCoeffs { mus 0.342; mud 0.557; I0 0.069; }";
const std::string table1BG =
    "frictionLaw BarkerGray; BarkerGrayCoeffs { mus 0.342; mud 0.557;"
    " muInf 0.05; I0 0.069; alpha 1.9; I1 0.004; }";

// Table 4
std::string table4(const word& law, const scalar I1)
{
    std::ostringstream os;
    os.precision(17);
    os << "frictionLaw " << law << "; " << law << "Coeffs { mus "
       << std::tan(20.16*deg) << "; mud " << std::tan(37.65*deg)
       << "; muInf 0.03; I0 0.5106; alpha 1.9; I1 " << I1 << "; }";
    return os.str();
}

void checkTable4Bound
(
    const word& law,
    const std::string& what,
    const label end,
    const scalar expected,
    const scalar relTol
)
{
    autoPtr<frictionLaw> law4(frictionLaw::New(parse(table4(law))));
    const List<Pair<scalar>> r4(wellPosedness::ranges(*law4));
    check(law + " table 4: one well-posed range", r4.size() == 1);
    if (r4.size() == 1)
    {
        checkClose(law + " table 4: " + what, r4[0][end], expected, relTol);
    }
}

std::string properties
(
    const scalar ds,
    const scalar dl,
    const std::string& law,
    const std::string& extra
)
{
    std::ostringstream os;
    os.precision(17);
    os  << "rhoStar 2500; Phi 0.6; etaMax 10; pMin 1e-8; " << extra
        << " grains { small { d " << ds << "; " << law << " }"
        << " large { d " << dl << "; " << law << " } }";
    return os.str();
}

scalar evalPair
(
    const std::string& family,
    const std::string& pairDict,
    const scalar ds,
    const scalar dl,
    const label a,
    const label b,
    const onePoint& pt
)
{
    const dictionary props(parse(properties(ds, dl)));
    const granularRheology rheology(props);
    const dictionary pd(parse(pairDict));
    scalarField result(1, -1.0);
    if (family == "segregation")
    {
        segregationVelocity::New(pd, rheology, a, b)->f(pt.state(), result);
    }
    else
    {
        diffusivity::New(pd, rheology, a, b)->D(pt.state(), result);
    }
    return result[0];
}

} // End namespace granularRheologyTest
} // End namespace Foam


// ************************************************************************* //
