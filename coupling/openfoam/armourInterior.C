/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourInterior.H"

#include <cmath>

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

    // Per body: which phases its cells hold, its cells' box and height
    // range, and its smallest cell (the layer height).
    List<scalar> lowAlpha(nBodies, GREAT), highAlpha(nBodies, -GREAT);
    List<vector> lo(nBodies, vector::uniform(GREAT));
    List<vector> hi(nBodies, vector::uniform(-GREAT));
    List<scalar> cell(nBodies, GREAT);
    forAll(C, i)
    {
        const label k = bodyOfCell[i];
        if (k < 0)
        {
            continue;
        }
        lowAlpha[k] = min(lowAlpha[k], alpha[i]);
        highAlpha[k] = max(highAlpha[k], alpha[i]);
        lo[k] = min(lo[k], C[i]);
        hi[k] = max(hi[k], C[i]);
        cell[k] = min(cell[k], std::cbrt(V[i]));
    }
    Pstream::listCombineGather(lowAlpha, minEqOp<scalar>());
    Pstream::listCombineScatter(lowAlpha);
    Pstream::listCombineGather(highAlpha, maxEqOp<scalar>());
    Pstream::listCombineScatter(highAlpha);
    Pstream::listCombineGather(lo, minEqOp<vector>());
    Pstream::listCombineScatter(lo);
    Pstream::listCombineGather(hi, maxEqOp<vector>());
    Pstream::listCombineScatter(hi);
    Pstream::listCombineGather(cell, minEqOp<scalar>());
    Pstream::listCombineScatter(cell);

    // Layers of height one cell from the bottom of each piercing body's
    // widened box; slot[k] is where body k's layers start in the sums.
    labelList slot(nBodies, -1);
    labelList layers(nBodies, 0);
    List<scalar> bottom(nBodies, Zero);
    label total = 0;
    for (label k = 0; k < nBodies; ++k)
    {
        if (lowAlpha[k] >= 0.5 || highAlpha[k] <= 0.5)
        {
            continue;
        }
        const vector margin = vector::uniform(1.5*cell[k]);
        lo[k] -= margin;
        hi[k] += margin;
        // The box's lowest and highest corners along up.
        scalar zlo = GREAT, zhi = -GREAT;
        for (label corner = 0; corner < 8; ++corner)
        {
            const vector x
            (
                (corner & 1) ? hi[k].x() : lo[k].x(),
                (corner & 2) ? hi[k].y() : lo[k].y(),
                (corner & 4) ? hi[k].z() : lo[k].z()
            );
            zlo = min(zlo, x & up);
            zhi = max(zhi, x & up);
        }
        bottom[k] = zlo;
        layers[k] = label(std::ceil((zhi - zlo)/cell[k])) + 2;
        slot[k] = total;
        total += layers[k];
    }
    if (total == 0)
    {
        return;
    }
    const auto layerOf = [&](label k, const vector& x)
    {
        return min
        (
            max(label(std::floor(((x & up) - bottom[k])/cell[k] + 0.5)), label(0)),
            layers[k] - 1
        );
    };

    // The free cells around each piercing body, layer by layer.
    List<scalar> water(total, Zero), volume(total, Zero);
    for (label k = 0; k < nBodies; ++k)
    {
        if (slot[k] < 0)
        {
            continue;
        }
        const boundBox box(lo[k], hi[k]);
        forAll(C, i)
        {
            if (bodyOfCell[i] < 0 && chi[i] <= 0 && box.contains(C[i]))
            {
                const label s = slot[k] + layerOf(k, C[i]);
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
        if (k < 0 || slot[k] < 0 || chi[i] < inside)
        {
            continue;
        }
        const label s = slot[k] + layerOf(k, C[i]);
        if (volume[s] > 0)
        {
            a[i] = water[s]/volume[s];
        }
    }
    alpha.correctBoundaryConditions();
}


// ************************************************************************* //
