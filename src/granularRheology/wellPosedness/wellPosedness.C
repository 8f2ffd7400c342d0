/*---------------------------------------------------------------------------*\
    granularSegregationFoam: coupled mu(I) rheology and size segregation
    Copyright (C) 2026 The granularSegregationFoam authors
    License: GNU General Public License v3 or later (see LICENSE)
\*---------------------------------------------------------------------------*/

#include "wellPosedness.H"
#include "DynamicList.H"

// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

Foam::scalar Foam::wellPosedness::condition
(
    const frictionLaw& law,
    const scalar I
)
{
    if (I <= 0)
    {
        // Limit I -> 0 of I mu' is 0 for every law here
        return condition(law.mu(0), 0);
    }
    return condition(law.mu(I), I*law.dmudI(I));
}


void Foam::wellPosedness::indicator
(
    const scalarField& I,
    const scalarField& mu,
    const scalarField& dmudI,
    scalarField& result
)
{
    forAll(I, i)
    {
        const scalar IdmudI = (I[i] > 0 ? I[i]*dmudI[i] : 0);
        result[i] = illPosed(mu[i], IdmudI) ? 1 : 0;
    }
}


Foam::List<Foam::Pair<Foam::scalar>> Foam::wellPosedness::ranges
(
    const frictionLaw& law,
    const scalar Imin,
    const scalar Imax,
    const label perDecade
)
{
    const scalar logMin = log10(Imin);
    const label n = label(ceil((log10(Imax) - logMin)*perDecade));

    auto wellPosedAt = [&law](const scalar I)
    {
        return condition(law, I) <= 0;
    };

    // Boundary between a and b (log-space bisection to round-off)
    auto boundary = [&wellPosedAt](scalar a, scalar b)
    {
        const bool wa = wellPosedAt(a);
        for (label iter = 0; iter < 200 && b - a > 4*SMALL*b; ++iter)
        {
            const scalar m = sqrt(a*b);
            if (m <= a || m >= b) break;
            (wellPosedAt(m) == wa ? a : b) = m;
        }
        return 0.5*(a + b);
    };

    DynamicList<Pair<scalar>> result;
    scalar Iprev = Imin;
    bool wPrev = wellPosedAt(Iprev);
    scalar start = Imin;

    for (label k = 1; k <= n; ++k)
    {
        const scalar Ik = min(pow(10, logMin + scalar(k)/perDecade), Imax);
        const bool wk = wellPosedAt(Ik);

        if (wk != wPrev)
        {
            const scalar Ib = boundary(Iprev, Ik);
            if (wk)
            {
                start = Ib;
            }
            else
            {
                result.append(Pair<scalar>(start, Ib));
            }
        }
        Iprev = Ik;
        wPrev = wk;
    }
    if (wPrev)
    {
        result.append(Pair<scalar>(start, Imax));
    }

    return List<Pair<scalar>>(std::move(result));
}


// ************************************************************************* //
