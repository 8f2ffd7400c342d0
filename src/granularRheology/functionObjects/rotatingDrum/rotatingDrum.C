/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "rotatingDrum.H"
#include "volFields.H"
#include "granularInput.H"
#include "gravityMeshObject.H"
#include "processorPolyPatch.H"
#include "unitConversion.H"
#include "addToRunTimeSelectionTable.H"

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * //

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(rotatingDrum, 0);
    addToRunTimeSelectionTable(functionObject, rotatingDrum, dictionary);
}
}


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void Foam::functionObjects::rotatingDrum::seed()
{
    const scalar tol = 1e-6*period_;
    for (const instant& inst : time_.times())
    {
        if
        (
            inst.value() > firstTime_ - period_ - tol
         && inst.value() < firstTime_ - tol
        )
        {
            IOobject io
            (
                fieldName_,
                inst.name(),
                mesh_,
                IOobject::MUST_READ,
                IOobject::NO_WRITE,
                false
            );
            if (io.typeHeaderOk<volScalarField>(true))
            {
                const volScalarField alpha(io, mesh_);
                times_.append(inst.value());
                samples_.append(alpha.primitiveField());
            }
        }
    }

    times_.append(firstTime_);
    samples_.append(lookupObject<volScalarField>(fieldName_).primitiveField());

    Log << type() << " " << name() << ": " << times_.size()
        << " sample(s) of " << fieldName_ << " to start J of (7.6)" << endl;
}


Foam::scalar Foam::functionObjects::rotatingDrum::changeOverPeriod
(
    const scalarField& alpha
) const
{
    // The sample of t - T, if the record reaches that far back
    const scalar t0 = time_.value() - period_;
    const scalar tol = 1e-6*period_;
    forAll(times_, i)
    {
        if (mag(times_[i] - t0) < tol)
        {
            // (7.6), normalised by the drum's area 4L^2 (its volume here)
            const scalarField& V = mesh_.V().field();
            return gSum(V*mag(alpha - samples_[i]))/gSum(V);
        }
    }

    // The record is complete from the start time on
    if (t0 > firstTime_ + tol)
    {
        FatalErrorInFunction
            << "No sample of " << fieldName_ << " at t - T = " << t0
            << " in function object " << name() << nl
            << exit(FatalError);
    }
    return GREAT;
}


Foam::scalar Foam::functionObjects::rotatingDrum::surfaceAngle() const
{
    const volScalarField& air = lookupObject<volScalarField>(airName_);
    const volVectorField& C = mesh_.C();
    const vector& a = rotation_.axis();
    const point& x0 = rotation_.origin();

    // Sums of the least-squares fit: n, sum x, sum x x^T
    scalar n = 0;
    vector sx(Zero);
    symmTensor sxx(Zero);
    const auto add = [&](const point& c1, const point& c2, scalar a1, scalar a2)
    {
        if ((a1 - 0.5)*(a2 - 0.5) >= 0)
        {
            return;
        }
        point x = c1 + (0.5 - a1)/(a2 - a1)*(c2 - c1) - x0;
        x -= (x & a)*a;
        if (mag(x) <= surfaceRadius_)
        {
            n += 1;
            sx += x;
            sxx += sqr(x);
        }
    };

    const labelUList& own = mesh_.owner();
    const labelUList& nei = mesh_.neighbour();
    forAll(nei, facei)
    {
        add(C[own[facei]], C[nei[facei]], air[own[facei]], air[nei[facei]]);
    }

    // Segments across processor boundaries, counted by the lower rank
    forAll(air.boundaryField(), patchi)
    {
        const fvPatchScalarField& ap = air.boundaryField()[patchi];
        const auto* pp = isA<processorPolyPatch>(ap.patch().patch());
        if (pp && pp->owner())
        {
            const scalarField aNbr(ap.patchNeighbourField());
            const vectorField cNbr(C.boundaryField()[patchi].patchNeighbourField());
            const labelUList& fc = ap.patch().faceCells();
            forAll(fc, i)
            {
                add(C[fc[i]], cNbr[i], air[fc[i]], aNbr[i]);
            }
        }
    }

    reduce(n, sumOp<scalar>());
    reduce(sx, sumOp<vector>());
    reduce(sxx, sumOp<symmTensor>());
    if (n < 2)
    {
        if (!noSurfaceReported_)
        {
            WarningInFunction
                << "function object " << name() << ": no free surface "
                << "(air fraction 1/2) within surfaceRadius "
                << surfaceRadius_ << " m of the drum's axis at t = "
                << time_.timeName() << "; the inclination is written as "
                << "nan until there is one (raise surfaceRadius to the "
                << "surface's distance from the axis)" << nl << endl;
            noSurfaceReported_ = true;
        }
        return GREAT;
    }

    // Direction of the line: the principal axis of the points' covariance
    const symmTensor cov(sxx/n - sqr(sx/n));
    const vector d(eigenVectors(cov).z());

    const vector gHat(normalised(meshObjects::gravity::New(time_).value()));
    return radToDeg(asin(min(mag(d & gHat)/max(mag(d), SMALL), 1.0)));
}


Foam::scalar Foam::functionObjects::rotatingDrum::peakSpeed() const
{
    const volScalarField& air = lookupObject<volScalarField>(airName_);
    const volVectorField& U = lookupObject<volVectorField>("U");

    const scalarField speed
    (
        mag
        (
            U.primitiveField()
          - rotation_.velocity(mesh_.C().primitiveField(), time_.value())
        )
    );
    return gMax(pos(0.5 - air.primitiveField())*speed);
}


void Foam::functionObjects::rotatingDrum::writeFileHeader(Ostream& os)
{
    writeHeader(os, "Rotating drum (section 7)");
    writeHeaderValue(os, "J of (7.6) of", fieldName_);
    writeHeaderValue(os, "period T [s]", period_);
    writeHeaderValue(os, "surfaceRadius [m]", surfaceRadius_);
    writeCommented(os, "Time");
    writeTabbed(os, "J");
    writeTabbed(os, "surfaceAngle[deg]");
    writeTabbed(os, "peakSpeed[m/s]");
    os  << endl;
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::functionObjects::rotatingDrum::rotatingDrum
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    fvMeshFunctionObject(name, runTime, dict),
    writeFile(mesh_, name, typeName, dict),
    rotation_(runTime),
    fieldName_(),
    airName_(),
    period_(0),
    surfaceRadius_(0),
    noSurfaceReported_(false),
    firstTime_(runTime.value()),
    times_(),
    samples_()
{
    read(dict);
    seed();
    writeFileHeader(file());
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

bool Foam::functionObjects::rotatingDrum::read(const dictionary& dict)
{
    fvMeshFunctionObject::read(dict);
    writeFile::read(dict);

    fieldName_ = dict.get<word>("field");
    airName_ = dict.getOrDefault<word>("air", "alpha.air");
    granularInput::requireFields(dict, "field", {fieldName_}, obr_);
    granularInput::requireFields(dict, "air", {airName_}, obr_);

    const scalar omega = mag(rotation_.omega(time_.value()));
    if (!dict.found("period") && omega < SMALL)
    {
        FatalIOErrorInFunction(dict)
            << "The drum does not turn (omega = 0 in dynamicMeshDict):"
            << " give the period of (7.6) in " << dict.name() << nl
            << exit(FatalIOError);
    }
    period_ = granularInput::readPositiveOrDefault
    (
        dict, "period", dimTime, omega > SMALL ? constant::mathematical::twoPi/omega : 1
    ).value();
    surfaceRadius_ =
        granularInput::readPositive(dict, "surfaceRadius", dimLength).value();

    // (7.6) compares samples one period apart: the write times must hit
    // t - T exactly
    const word control(dict.getOrDefault<word>("writeControl", "timeStep"));
    if (control != "adjustableRunTime")
    {
        FatalIOErrorInFunction(dict)
            << "writeControl = " << control << " in " << dict.name()
            << ": J of (7.6) needs writeControl adjustableRunTime" << nl
            << exit(FatalIOError);
    }
    const scalar interval =
        granularInput::readPositive(dict, "writeInterval", dimTime).value();
    const scalar ratio = period_/interval;
    if (mag(ratio - std::round(ratio)) > 1e-9*ratio)
    {
        FatalIOErrorInFunction(dict)
            << "writeInterval = " << interval << " in " << dict.name()
            << ": it must divide the period " << period_ << " of (7.6)"
            << nl << exit(FatalIOError);
    }

    return true;
}


bool Foam::functionObjects::rotatingDrum::write()
{
    const scalar t = time_.value();
    const scalarField& alpha =
        lookupObject<volScalarField>(fieldName_).primitiveField();

    const scalar J = changeOverPeriod(alpha);
    const scalar angle = surfaceAngle();
    const scalar speed = peakSpeed();

    // Keep the samples of the last revolution only
    const scalar tol = 1e-6*period_;
    label keep = 0;
    forAll(times_, i)
    {
        if (times_[i] > t - period_ - tol)
        {
            times_[keep] = times_[i];
            samples_[keep].transfer(samples_[i]);
            ++keep;
        }
    }
    times_.resize(keep);
    samples_.resize(keep);
    times_.append(t);
    samples_.append(alpha);

    // GREAT marks a value that does not exist yet: written as nan
    const auto put = [](Ostream& os, const scalar x) -> Ostream&
    {
        if (x < 0.1*GREAT)
        {
            os << x;
        }
        else
        {
            os << "nan";
        }
        return os;
    };

    if (log)
    {
        Info<< type() << " " << name() << " write: J = ";
        put(Info, J) << ", surface angle = ";
        put(Info, angle) << " deg, peak speed = " << speed << " m/s" << endl;
    }

    if (Pstream::master())
    {
        OFstream& os = file();
        writeCurrentTime(os);
        os << tab;
        put(os, J) << tab;
        put(os, angle) << tab << speed << endl;
    }

    return true;
}


// ************************************************************************* //
