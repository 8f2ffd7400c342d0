/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Application
    granularWellPosedness

Group
    grpGranularUtilities

Description
    Prints, for each grain phase of a rheology dictionary, the ranges of
    inertial number in which the incompressible mu(I)-rheology is well posed
    by (2.6) of Barker et al. (2021) (ERRATA item 1), and I_max.  For the
    partially regularised law (2.8) it also prints the range of the
    unregularised law (2.7) with the same mu_s, mu_d, I_0, whose lower bound
    is where I_1 belongs.

Usage
    granularWellPosedness [-dict file] [-Imin 1e-9] [-Imax 1e4]

    The default dictionary is constant/granularProperties of the case.

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "Time.H"
#include "IOdictionary.H"
#include "granularRheology.H"
#include "BarkerGray.H"
#include "Jop.H"
#include "wellPosedness.H"
#include "IStringStream.H"
#include "OFstream.H"

using namespace Foam;

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

void printRanges
(
    const frictionLaw& law,
    const scalar Imin,
    const scalar Imax,
    const word& indent
)
{
    const List<Pair<scalar>> ranges(wellPosedness::ranges(law, Imin, Imax));

    if (ranges.empty())
    {
        Info<< indent << "ill posed for every I in [" << Imin << ", " << Imax
            << "]" << nl;
        return;
    }

    for (const Pair<scalar>& r : ranges)
    {
        Info<< indent << "well posed for I in [";
        if (r.first() == Imin && law.creeps())
        {
            Info<< "0";
        }
        else
        {
            Info<< r.first();
        }
        Info<< ", " << r.second() << "]";
        if (r.second() == Imax)
        {
            Info<< " (to the end of the scan)";
        }
        Info<< nl;
    }

    const scalar upper = ranges.last().second();
    if (upper < Imax)
    {
        Info<< indent << "I_max = " << upper << nl;
    }
}


void writeTable
(
    const granularRheology& rheology,
    const scalar Imin,
    const scalar Imax,
    const label nPoints,
    const fileName& path
)
{
    OFstream os(path);
    os.precision(12);
    os  << "# I";
    for (const word& name : rheology.names())
    {
        os  << " mu." << name << " wellPosed." << name;
    }
    os  << nl;
    for (label k = 0; k < nPoints; ++k)
    {
        const scalar I =
            Imin*Foam::pow(Imax/Imin, scalar(k)/max(nPoints - 1, 1));
        os  << I;
        forAll(rheology.names(), i)
        {
            const frictionLaw& law = rheology.law(i);
            const scalar mu = law.mu(I);
            os  << ' ' << mu << ' '
                << (wellPosedness::illPosed(mu, I*law.dmudI(I)) ? 0 : 1);
        }
        os  << nl;
    }
    Info<< nl << "Wrote mu(I) at " << nPoints << " points to " << path << nl;
}


//- The file of a command-line option, relative to the case
fileName optionPath(const argList& args, const word& option)
{
    fileName path(args.get<fileName>(option).expand());
    if (!path.isAbsolute())
    {
        path = args.path()/path;
    }
    return path;
}


//- The well-posed ranges of one grain phase's law and, for the partially
//  regularised law (2.8), of the unregularised (2.7) with the same mus, mud,
//  I0
void printPhase
(
    const word& name,
    const frictionLaw& law,
    const scalar Imin,
    const scalar Imax
)
{
    Info<< nl << "grain phase " << name << ": frictionLaw " << law.type()
        << nl;

    printRanges(law, Imin, Imax, "    ");

    if (!isA<frictionLaws::BarkerGray>(law))
    {
        return;
    }
    const auto& c = refCast<const frictionLaws::BarkerGray>(law).coeffs();
    OStringStream os;
    os.precision(17);
    os  << "frictionLaw Jop; JopCoeffs { mus "
        << c[frictionLaws::BarkerGray::MUS]
        << "; mud " << c[frictionLaws::BarkerGray::MUD]
        << "; I0 " << c[frictionLaws::BarkerGray::I0] << "; }";
    IStringStream is(os.str());
    const frictionLaws::Jop jop((dictionary(is)));

    Info<< "    unregularised law (2.7) with the same mus, mud, I0:" << nl;
    printRanges(jop, Imin, Imax, "        ");
    Info<< "    I1 = " << c[frictionLaws::BarkerGray::I1] << nl;
}


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Well-posed inertial-number ranges of each grain phase's friction law"
        " (Barker et al. 2021, (2.6))"
    );
    argList::noParallel();
    argList::addOption
    (
        "dict", "file", "Rheology dictionary [constant/granularProperties]"
    );
    argList::addOption("Imin", "scalar", "Lower end of the scan [1e-9]");
    argList::addOption("Imax", "scalar", "Upper end of the scan [1e4]");
    argList::addOption
    (
        "table", "file", "Write mu(I) and its well-posedness to this file"
    );
    argList::addOption("points", "label", "Points of the table [600]");

    #include "setRootCase.H"
    #include "createTime.H"

    const scalar Imin = args.getOrDefault<scalar>("Imin", 1e-9);
    const scalar Imax = args.getOrDefault<scalar>("Imax", 1e4);
    if (!(Imin > 0 && Imax > Imin))
    {
        FatalErrorInFunction
            << "Invalid values of options -Imin " << Imin << " and -Imax "
            << Imax << ": 0 < Imin < Imax" << nl << exit(FatalError);
    }

    const fileName dictPath
    (
        args.found("dict")
      ? optionPath(args, "dict")
      : fileName(runTime.constant()/"granularProperties")
    );

    const IOdictionary dict
    (
        IOobject
        (
            dictPath,
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    );

    const granularRheology rheology(dict);

    Info<< nl << "Well-posedness (2.6) of " << dictPath << nl;

    forAll(rheology.names(), i)
    {
        printPhase(rheology.names()[i], rheology.law(i), Imin, Imax);
    }

    if (args.found("table"))
    {
        const label nPoints = args.getOrDefault<label>("points", 600);
        if (nPoints < 2)
        {
            FatalErrorInFunction
                << "Invalid value of option -points: " << nPoints
                << " (at least 2)" << nl << exit(FatalError);
        }
        writeTable(rheology, Imin, Imax, nPoints, optionPath(args, "table"));
    }

    Info<< nl << "End" << nl << endl;

    return 0;
}


// ************************************************************************* //
