/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "granularPhases.H"
#include "granularRheology.H"

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{
    //- Number of values (over all processors) with a non-finite component
    template<class Type>
    Foam::label nonFinite(const Foam::Field<Type>& values)
    {
        using namespace Foam;
        label n = 0;
        for (const Type& v : values)
        {
            for (direction c = 0; c < pTraits<Type>::nComponents; ++c)
            {
                if (!std::isfinite(component(v, c)))
                {
                    ++n;
                    break;
                }
            }
        }
        return returnReduce(n, sumOp<label>());
    }
}


// * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * * //

void Foam::granularPhases::checkFiles(const dictionary& dict) const
{
    // Each phase fraction is dimensionless
    for (const volScalarField& alpha : alphas_)
    {
        if (alpha.dimensions() != dimless)
        {
            FatalIOError
            (
                FUNCTION_NAME, __FILE__, __LINE__, alpha.objectPath()
            )   << "Invalid value of keyword 'dimensions' in file "
                << alpha.objectPath() << ": dimensions = "
                << alpha.dimensions() << "; a phase fraction is"
                << " dimensionless, " << dimless << nl
                << exit(FatalIOError);
        }
    }

    // A fraction file that no phase reads: a misspelt or left-over phase
    wordList names(alphas_.size());
    forAll(alphas_, i)
    {
        names[i] = alphas_[i].name();
    }
    const fileName dir(mesh_.time().timePath());
    for (const fileName& f : readDir(dir, fileName::FILE))
    {
        const word name(f.ext() == "gz" ? f.lessExt() : f);
        if (name.starts_with("alpha.") && !names.found(name))
        {
            WarningInFunction
                << dir/f << " is not read: it matches no phase of "
                << dict.name() << " (the phases read: " << names
                << ")" << endl;
        }
    }
}


void Foam::granularPhases::checkFractions() const
{
    const scalar tol = 1e-6;
    scalarField sum(mesh_.nCells(), Zero);

    for (const volScalarField& alpha : alphas_)
    {
        const scalar lo = gMin(alpha.primitiveField());
        const scalar hi = gMax(alpha.primitiveField());
        if (lo < -tol || hi > 1 + tol)
        {
            FatalErrorInFunction
                << "Invalid initial field " << alpha.objectPath()
                << ": values in [" << lo << ", " << hi << "], outside [0, 1]"
                << nl << exit(FatalError);
        }
        sum += alpha.primitiveField();
    }

    const scalar err = gMax(mag(sum - 1.0)());
    if (err > tol)
    {
        FatalErrorInFunction
            << "Invalid initial phase fractions in "
            << mesh_.time().timePath() << ": the fractions of "
            << alphas_.size() << " phases (alpha.*) must sum to 1, but"
            << " |sum - 1| reaches " << err << " (tolerance " << tol << ")"
            << nl << exit(FatalError);
    }
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::granularPhases::granularPhases
(
    const fvMesh& mesh,
    const dictionary& dict,
    const word& airName,
    const granularRheology& rheology
)
:
    mesh_(mesh),
    rheology_(rheology)
{
    const wordList& grains = rheology_.names();
    if (grains.found(airName))
    {
        FatalIOErrorInFunction(dict)
            << "Invalid value of keyword 'name' in dictionary "
            << dict.subDict("air").name() << ": name = " << airName
            << " is also a grain phase " << grains << nl
            << exit(FatalIOError);
    }

    alphas_.setSize(1 + grains.size());
    alphaPhis_.setSize(alphas_.size());
    forAll(alphas_, i)
    {
        const word phaseName(i == 0 ? airName : grains[i - 1]);
        alphas_.set
        (
            i,
            new volScalarField
            (
                IOobject
                (
                    IOobject::groupName("alpha", phaseName),
                    mesh_.time().timeName(),
                    mesh_,
                    IOobject::MUST_READ,
                    IOobject::AUTO_WRITE
                ),
                mesh_
            )
        );
    }
    checkFiles(dict);
    checkFractions();

    forAll(alphaPhis_, i)
    {
        alphaPhis_.set
        (
            i,
            new surfaceScalarField
            (
                IOobject
                (
                    "alphaPhi." + alphas_[i].name(),
                    mesh_.time().timeName(),
                    mesh_,
                    IOobject::NO_READ,
                    IOobject::NO_WRITE
                ),
                mesh_,
                dimensionedScalar(dimVolume/dimTime, Zero)
            )
        );
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::granularPhases::grainFractions(PtrList<scalarField>& c) const
{
    UPtrList<const scalarField> grainAlphas(alphas_.size() - 1);
    for (label i = 1; i < alphas_.size(); ++i)
    {
        grainAlphas.set(i - 1, &alphas_[i].primitiveField());
    }
    rheology_.grainFractions(grainAlphas, c);
}


Foam::tmp<Foam::volScalarField> Foam::granularPhases::nearInterface() const
{
    auto tnear = tmp<volScalarField>::New
    (
        IOobject("nearInterface", mesh_.time().timeName(), mesh_),
        mesh_,
        dimensionedScalar(dimless, Zero)
    );

    for (const volScalarField& alpha : alphas_)
    {
        tnear.ref() = max(tnear(), pos0(alpha - 0.01)*pos0(0.99 - alpha));
    }
    return tnear;
}


Foam::scalar Foam::granularPhases::segregationIndex() const
{
    const label nGrains = alphas_.size() - 1;
    if (nGrains < 2)
    {
        return -1;
    }

    // The fractions clipped at zero: MULES leaves round-off below zero
    // (-1e-13) where it undershoots, in the air above all.  The weight of a
    // cell is its grain volume, the concentrations c^i those of the
    // rheology, in [0, 1] and uniform where there are no grains.
    scalarField alphaG(mesh_.nCells(), Zero);
    for (label i = 1; i < alphas_.size(); ++i)
    {
        alphaG += max(alphas_[i].primitiveField(), scalar(0));
    }
    const scalarField w(mesh_.V().field()*alphaG);
    const scalar W = gSum(w);
    if (W <= VSMALL)
    {
        return -1;
    }

    PtrList<scalarField> c;
    grainFractions(c);
    scalar variance = 0;
    scalar mixed = 0;
    for (const scalarField& ci : c)
    {
        const scalar cMean = gSum(w*ci)/W;
        variance += gSum(w*sqr(ci - cMean))/W;
        mixed += cMean*(1 - cMean);
    }

    // variance sums terms >= 0 (the weights are); max keeps the root real
    // whatever the round-off
    return mixed > SMALL ? Foam::sqrt(max(variance, scalar(0))/mixed) : 0;
}


void Foam::granularPhases::report() const
{
    Info<< "Phase volumes:";
    for (const volScalarField& alpha : alphas_)
    {
        Info<< ' ' << alpha.name() << " = "
            << gSum(mesh_.V().field()*alpha.primitiveField());
    }
    Info<< nl;

    const scalar S = segregationIndex();
    if (S >= 0)
    {
        Info<< "Segregation index (0 mixed, 1 segregated) = " << S << nl;
    }
}


void Foam::granularPhases::reportBounds() const
{
    scalarField sumAlpha(mesh_.nCells(), Zero);
    for (const volScalarField& alpha : alphas_)
    {
        Info<< "    " << alpha.name() << " volume = "
            << gSum(mesh_.V().field()*alpha.primitiveField())
            << " min = " << gMin(alpha.primitiveField())
            << " max = " << gMax(alpha.primitiveField()) << nl;
        sumAlpha += alpha.primitiveField();
    }
    Info<< "    sum of phase fractions: min = " << gMin(sumAlpha)
        << " max = " << gMax(sumAlpha) << endl;
}


void Foam::granularPhases::checkFinite
(
    const volVectorField& U,
    const volScalarField& p
) const
{
    DynamicList<word> bad;
    DynamicList<label> n;
    const auto check = [&](const word& name, const label k)
    {
        if (k)
        {
            bad.append(name);
            n.append(k);
        }
    };
    check(U.name(), nonFinite(U.primitiveField()));
    check(p.name(), nonFinite(p.primitiveField()));
    for (const volScalarField& alpha : alphas_)
    {
        check(alpha.name(), nonFinite(alpha.primitiveField()));
    }

    if (bad.size())
    {
        FatalErrorInFunction
            << "Non-finite values (NaN or Inf) at time "
            << mesh_.time().timeName() << " in " << bad << ", in "
            << n << " cells: stopping before they are written" << nl
            << exit(FatalError);
    }
}


// ************************************************************************* //
