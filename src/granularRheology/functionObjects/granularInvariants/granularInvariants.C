/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularInvariants.H"
#include "volFields.H"
#include "uniformDimensionedFields.H"
#include "surfaceFields.H"
#include "granularInput.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(granularInvariants, 0);

    //- The solver's lowest grain pressure of the step (granularMixture)
    //  and the relative sums of the fluxes over the phases (2.12)
    //  (granularTransport): the values the solver registers, each a column
    //  when present
    static const wordList solverValues
    ({
        "grainPressureMin", "pairwiseFluxSum", "limitedFluxSum"
    });
    static const wordList solverColumns
    ({
        "minGrainPressure", "pairwiseFluxSum", "limitedFluxSum"
    });
    addToRunTimeSelectionTable(functionObject, granularInvariants, dictionary);
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

Foam::scalar Foam::functionObjects::granularInvariants::volume
(
    const volScalarField& alpha
) const
{
    return gSum(mesh_.V().field()*alpha.primitiveField());
}


Foam::scalar Foam::functionObjects::granularInvariants::outflow
(
    const word& phase
) const
{
    const word fluxName("alphaPhi." + phase);
    if (!foundObject<surfaceScalarField>(fluxName))
    {
        return 0;
    }
    const surfaceScalarField& flux = lookupObject<surfaceScalarField>(fluxName);

    // Faces between processors carry no net flux out of the domain
    scalar out = 0;
    forAll(flux.boundaryField(), patchi)
    {
        const fvsPatchScalarField& pf = flux.boundaryField()[patchi];
        if (!pf.coupled())
        {
            out += sum(pf);
        }
    }
    return returnReduce(out, sumOp<scalar>());
}


void Foam::functionObjects::granularInvariants::writeFileHeader(Ostream& os)
{
    writeHeader(os, "Invariants of the phase transport");
    writeCommented(os, "Time");
    for (const word& phase : phases_)
    {
        writeTabbed(os, "balance(" + phase + ")");
        writeTabbed(os, "min(" + phase + ")");
        writeTabbed(os, "max(" + phase + ")");
    }
    writeTabbed(os, "max|sum-1|");
    writeTabbed(os, "nonFinite");
    forAll(solverValues, k)
    {
        if (foundObject<uniformDimensionedScalarField>(solverValues[k]))
        {
            writeTabbed(os, solverColumns[k]);
        }
    }
    os  << endl;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::functionObjects::granularInvariants::granularInvariants
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    fvMeshFunctionObject(name, runTime, dict),
    writeFile(mesh_, name, typeName, dict),
    phases_(),
    V0_(),
    outflow_(),
    timeIndex_(runTime.timeIndex())
{
    read(dict);

    // The balance starts here (a re-read of the dictionary keeps it)
    V0_.setSize(phases_.size());
    outflow_.setSize(phases_.size(), Zero);
    forAll(phases_, i)
    {
        V0_[i] = volume(lookupObject<volScalarField>(phases_[i]));
    }
    writeFileHeader(file());
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::functionObjects::granularInvariants::read(const dictionary& dict)
{
    fvMeshFunctionObject::read(dict);
    writeFile::read(dict);

    const wordList phases(dict.get<wordList>("phases"));
    if (phases_.size() && phases != phases_)
    {
        FatalIOErrorInFunction(dict)
            << "phases = " << phases << " in " << dict.name() << ": the"
            << " phases cannot change during a run (were " << phases_ << ")"
            << nl << exit(FatalIOError);
    }
    phases_ = phases;
    if (phases_.empty())
    {
        FatalIOErrorInFunction(dict)
            << "phases = () in " << dict.name() << ": name the phase"
            << " fractions to monitor" << nl << exit(FatalIOError);
    }
    granularInput::requireFields(dict, "phases", phases_, obr_);

    return true;
}


bool Foam::functionObjects::granularInvariants::execute()
{
    // Once per time step: the flux of the step just made, times its dt
    if (time_.timeIndex() != timeIndex_)
    {
        timeIndex_ = time_.timeIndex();
        forAll(phases_, i)
        {
            outflow_[i] += time_.deltaTValue()*outflow(phases_[i]);
        }
    }
    return true;
}


bool Foam::functionObjects::granularInvariants::write()
{
    const scalar Vsmall = 1e-3*gSum(mesh_.V().field());

    scalarField sumAlpha(mesh_.nCells(), Zero);
    label nonFinite = 0;
    if (Pstream::master())
    {
        writeCurrentTime(file());
    }
    forAll(phases_, i)
    {
        const volScalarField& alpha = lookupObject<volScalarField>(phases_[i]);
        const scalarField& a = alpha.primitiveField();
        sumAlpha += a;
        for (const scalar x : a)
        {
            if (!std::isfinite(x))
            {
                ++nonFinite;
            }
        }

        const scalar balance =
            (volume(alpha) - V0_[i] + outflow_[i])/max(V0_[i], Vsmall);
        const scalar lo = gMin(a);
        const scalar hi = gMax(a);
        if (Pstream::master())
        {
            file() << tab << balance << tab << lo << tab << hi;
        }
    }
    reduce(nonFinite, sumOp<label>());
    const scalar sumErr = gMax(mag(sumAlpha - 1.0)());
    if (Pstream::master())
    {
        file() << tab << sumErr << tab << nonFinite;
        for (const word& name : solverValues)
        {
            const auto* v = findObject<uniformDimensionedScalarField>(name);
            if (v)
            {
                file() << tab << v->value();
            }
        }
        file() << endl;
    }
    return true;
}


// ************************************************************************* //
