/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "meshRotation.H"
#include "IOdictionary.H"

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::meshRotation::meshRotation(const Time& runTime)
:
    origin_(Zero),
    axis_(Zero),
    omega_()
{
    const IOdictionary meshDict
    (
        IOobject
        (
            "dynamicMeshDict",
            runTime.constant(),
            runTime,
            IOobject::MUST_READ,
            IOobject::NO_WRITE,
            false
        )
    );

    // The motion the solver applies: solidBody with rotatingMotion
    const word solver(meshDict.get<word>("motionSolver"));
    if (solver != "solidBody")
    {
        FatalIOErrorInFunction(meshDict)
            << "motionSolver = " << solver << " in " << meshDict.name()
            << ": a drum needs motionSolver solidBody with"
            << " solidBodyMotionFunction rotatingMotion" << nl
            << exit(FatalIOError);
    }

    const dictionary& solidDict = meshDict.subDict(solver + "Coeffs");
    const word function(solidDict.get<word>("solidBodyMotionFunction"));
    if (function != "rotatingMotion")
    {
        FatalIOErrorInFunction(solidDict)
            << "solidBodyMotionFunction = " << function << " in "
            << solidDict.name() << ": only rotatingMotion is a drum"
            << nl << exit(FatalIOError);
    }

    const dictionary& coeffs = solidDict.subDict(function + "Coeffs");
    origin_ = coeffs.get<point>("origin");
    axis_ = coeffs.get<vector>("axis");
    if (mag(axis_) < SMALL)
    {
        FatalIOErrorInFunction(coeffs)
            << "axis = " << axis_ << " in " << coeffs.name()
            << ": the axis of rotation must not be zero" << nl
            << exit(FatalIOError);
    }
    axis_ /= mag(axis_);
    omega_ = Function1<scalar>::New("omega", coeffs);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

Foam::tmp<Foam::vectorField> Foam::meshRotation::velocity
(
    const pointField& x,
    const scalar t
) const
{
    // (7.2), (7.3): the rigid rotation Omega a x (x - x_0)
    return (omega(t)*axis_) ^ (x - origin_);
}


// ************************************************************************* //
