/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)

Application
    Test-granularRheology

Description
    Unit tests of libgranularRheology against the numbers of Barker et al.
    (2021): one-point checks of every law in every run-time selection table,
    the rheology chain, and the refusal of bad input (granularRheologyTest.H
    lists the groups, one file each).  Prints one line per
    check and "N passed, M failed"; exits non-zero if any check failed.

    A law registered in a selection table without an entry in lawTests
    below is itself a failed check.

\*---------------------------------------------------------------------------*/

#include "argList.H"
#include "HashTable.H"
#include "granularRheologyTest.H"
#include "segregationVelocity.H"
#include "diffusivity.H"

using namespace Foam;
using namespace Foam::granularRheologyTest;

// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //

int main(int argc, char *argv[])
{
    argList::noBanner();
    argList::noParallel();
    argList args(argc, argv, false, false, false);

    typedef HashTable<std::function<void()>> testTable;

    const HashTable<testTable> lawTests
    {
        {
            "frictionLaw",
            testTable
            {
                {"constant", testConstantFriction},
                {"Jop", testJop},
                {"BarkerGray", testBarkerGray},
            }
        },
        {
            "segregationVelocity",
            testTable
            {
                {"constant", testConstantSegregation},
                {"Trewhela", testTrewhela},
            }
        },
        {
            "diffusivity",
            testTable
            {
                {"constant", testConstantDiffusivity},
                {"UtterBehringer", testUtterBehringer},
            }
        },
    };

    const HashTable<wordList> registered
    {
        {"frictionLaw", frictionLaw::dictionaryConstructorTablePtr_->sortedToc()},
        {"segregationVelocity", segregationVelocity::dictionaryConstructorTablePtr_->sortedToc()},
        {"diffusivity", diffusivity::dictionaryConstructorTablePtr_->sortedToc()},
    };

    forAllConstIters(registered, iter)
    {
        const testTable& tests = lawTests[iter.key()];
        for (const word& law : iter.val())
        {
            const std::string name = iter.key() + " " + law;
            check
            (
                "registered " + name + " has a test entry",
                tests.found(law),
                "no test for " + name + ": add one to lawTests"
            );
            if (tests.found(law))
            {
                tests[law]();
            }
        }
    }

    testChain();
    testStratified();
    testBadInput();
    testRandomProperties();

    Info<< nl << nPassed() << " passed, " << nFailed() << " failed" << endl;

    // A plain return from main was measured to give exit status 0 here
    // even with failures; exit() passes the status on
    std::exit(nFailed() ? 1 : 0);
}


// ************************************************************************* //