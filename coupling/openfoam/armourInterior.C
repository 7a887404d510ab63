/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourInterior.H"

#include <cmath>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{
    using namespace Foam;

    //- Per body, over all ranks: which phases its cells hold, its cells'
    //  box, and its smallest cell (the layer height)
    struct bodyCells
    {
        List<scalar> lowAlpha, highAlpha;
        List<vector> lo, hi;
        List<scalar> cell;

        bodyCells(label nBodies)
        :
            lowAlpha(nBodies, GREAT),
            highAlpha(nBodies, -GREAT),
            lo(nBodies, vector::uniform(GREAT)),
            hi(nBodies, vector::uniform(-GREAT)),
            cell(nBodies, GREAT)
        {}
    };

    bodyCells gatherBodyCells
    (
        const fvMesh& mesh,
        const std::vector<int>& bodyOfCell,
        label nBodies,
        const volScalarField& alpha
    )
    {
        const vectorField& C = mesh.C();
        const scalarField& V = mesh.V();
        bodyCells b(nBodies);
        forAll(C, i)
        {
            const label k = bodyOfCell[i];
            if (k < 0)
            {
                continue;
            }
            b.lowAlpha[k] = min(b.lowAlpha[k], alpha[i]);
            b.highAlpha[k] = max(b.highAlpha[k], alpha[i]);
            b.lo[k] = min(b.lo[k], C[i]);
            b.hi[k] = max(b.hi[k], C[i]);
            b.cell[k] = min(b.cell[k], std::cbrt(V[i]));
        }
        Pstream::listCombineGather(b.lowAlpha, minEqOp<scalar>());
        Pstream::listCombineScatter(b.lowAlpha);
        Pstream::listCombineGather(b.highAlpha, maxEqOp<scalar>());
        Pstream::listCombineScatter(b.highAlpha);
        Pstream::listCombineGather(b.lo, minEqOp<vector>());
        Pstream::listCombineScatter(b.lo);
        Pstream::listCombineGather(b.hi, maxEqOp<vector>());
        Pstream::listCombineScatter(b.hi);
        Pstream::listCombineGather(b.cell, minEqOp<scalar>());
        Pstream::listCombineScatter(b.cell);
        return b;
    }

    //- Layers of height one cell from the bottom of each piercing body's
    //  widened box; slot[k] is where body k's layers start in the sums
    //  (-1: body k does not pierce the surface)
    struct bodyLayers
    {
        labelList slot, layers;
        List<scalar> bottom;
        label total = 0;

        //- The layer of point x of body k
        label of(label k, const vector& x, const vector& up, scalar cell) const
        {
            return min
            (
                max(label(std::floor(((x & up) - bottom[k])/cell + 0.5)), label(0)),
                layers[k] - 1
            );
        }
    };

    //- Widens each piercing body's box (b.lo, b.hi) by 1.5 cells and lays
    //  its layers out
    bodyLayers layOutLayers(bodyCells& b, label nBodies, const vector& up)
    {
        bodyLayers l;
        l.slot = labelList(nBodies, -1);
        l.layers = labelList(nBodies, 0);
        l.bottom = List<scalar>(nBodies, Zero);
        for (label k = 0; k < nBodies; ++k)
        {
            if (b.lowAlpha[k] >= 0.5 || b.highAlpha[k] <= 0.5)
            {
                continue;
            }
            const vector margin = vector::uniform(1.5*b.cell[k]);
            b.lo[k] -= margin;
            b.hi[k] += margin;
            // The box's lowest and highest corners along up.
            scalar zlo = GREAT, zhi = -GREAT;
            for (label corner = 0; corner < 8; ++corner)
            {
                const vector x
                (
                    (corner & 1) ? b.hi[k].x() : b.lo[k].x(),
                    (corner & 2) ? b.hi[k].y() : b.lo[k].y(),
                    (corner & 4) ? b.hi[k].z() : b.lo[k].z()
                );
                zlo = min(zlo, x & up);
                zhi = max(zhi, x & up);
            }
            l.bottom[k] = zlo;
            l.layers[k] = label(std::ceil((zhi - zlo)/b.cell[k])) + 2;
            l.slot[k] = l.total;
            l.total += l.layers[k];
        }
        return l;
    }
}


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

void armourFoam::mirrorInterior
(
    const Foam::fvMesh& mesh,
    const std::vector<int>& bodyOfCell,
    const Foam::scalarField& chi,
    Foam::label nBodies,
    const Foam::vector& up,
    Foam::volScalarField& alpha
)
{
    using namespace Foam;
    const vectorField& C = mesh.C();
    const scalarField& V = mesh.V();
    const scalar inside = 1 - 1e-9;

    bodyCells b(gatherBodyCells(mesh, bodyOfCell, nBodies, alpha));
    const bodyLayers l(layOutLayers(b, nBodies, up));
    if (l.total == 0)
    {
        return;
    }

    // The free cells around each piercing body, layer by layer.
    List<scalar> water(l.total, Zero), volume(l.total, Zero);
    for (label k = 0; k < nBodies; ++k)
    {
        if (l.slot[k] < 0)
        {
            continue;
        }
        const boundBox box(b.lo[k], b.hi[k]);
        forAll(C, i)
        {
            if (bodyOfCell[i] < 0 && chi[i] <= 0 && box.contains(C[i]))
            {
                const label s = l.slot[k] + l.of(k, C[i], up, b.cell[k]);
                water[s] += alpha[i]*V[i];
                volume[s] += V[i];
            }
        }
    }
    Pstream::listCombineGather(water, plusEqOp<scalar>());
    Pstream::listCombineScatter(water);
    Pstream::listCombineGather(volume, plusEqOp<scalar>());
    Pstream::listCombineScatter(volume);

    scalarField& a = alpha.primitiveFieldRef();
    forAll(C, i)
    {
        const label k = bodyOfCell[i];
        if (k < 0 || l.slot[k] < 0 || chi[i] < inside)
        {
            continue;
        }
        const label s = l.slot[k] + l.of(k, C[i], up, b.cell[k]);
        if (volume[s] > 0)
        {
            a[i] = water[s]/volume[s];
        }
    }
    alpha.correctBoundaryConditions();
}


// ************************************************************************* //
