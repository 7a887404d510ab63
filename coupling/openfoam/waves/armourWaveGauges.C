/*---------------------------------------------------------------------------*\
    armour-fsi: free-surface wave gauges (armourWaveGauges.H)
\*---------------------------------------------------------------------------*/

#include "armourWaveGauges.H"
#include "addToRunTimeSelectionTable.H"
#include "gravityMeshObject.H"
#include "volFields.H"
#include "OSspecific.H"
#include "FixedList.H"
#include "vector2D.H"

namespace Foam
{
namespace functionObjects
{
    defineTypeNameAndDebug(armourWaveGauges, 0);
    addToRunTimeSelectionTable(functionObject, armourWaveGauges, dictionary);
}
}


void Foam::functionObjects::armourWaveGauges::findColumns()
{
    const vector g(meshObjects::gravity::New(mesh_.time()).value());
    ez_ = -g/(mag(g) + VSMALL);

    // Two horizontal axes: any pair orthogonal to ez.
    vector e1 = (mag(ez_.x()) < 0.9) ? vector(1, 0, 0) : vector(0, 1, 0);
    e1 -= (e1 & ez_)*ez_;
    e1 /= mag(e1);
    const vector e2 = ez_ ^ e1;

    // blockMesh puts the points of one internal face at coordinates that
    // differ by rounding (y = +-1e-18 on the mid plane of 12 cells across
    // -0.124..0.124), so a gauge exactly on a face fell in the bounding boxes
    // of the cells on both sides in some layers, whose water then counted
    // twice (0.52 and 0.78 m read for 0.40 m). The gauge is therefore tested
    // a hair off the face, on the +e1, +e2 side (the - side at the domain's
    // far edges): one rule, the same in every layer and on every rank, far
    // above rounding and far below any cell.
    const pointField& pts = mesh_.points();
    scalar aMax = -GREAT, bMax = -GREAT;
    for (const point& pt : pts)
    {
        aMax = max(aMax, pt & e1);
        bMax = max(bMax, pt & e2);
    }
    reduce(aMax, maxOp<scalar>());
    reduce(bMax, maxOp<scalar>());
    tol_ = 1e-9*mag(mesh_.bounds().span());  // bounds(): global

    scalarList ga(gauges_.size()), gb(gauges_.size());
    forAll(gauges_, gi)
    {
        const scalar a = gauges_[gi] & e1;
        const scalar b = gauges_[gi] & e2;
        ga[gi] = (a + tol_ < aMax) ? a + tol_ : a - tol_;
        gb[gi] = (b + tol_ < bMax) ? b + tol_ : b - tol_;
    }

    List<DynamicList<vector>> local(localColumns(e1, e2, ga, gb));
    columnZ_.setSize(gauges_.size());
    localCells_.setSize(gauges_.size());
    localSlots_.setSize(gauges_.size());
    forAll(gauges_, gi)
    {
        keepLayers(gi, local[gi]);
    }
}


Foam::List<Foam::DynamicList<Foam::vector>>
Foam::functionObjects::armourWaveGauges::localColumns
(
    const vector& e1,
    const vector& e2,
    const scalarList& ga,
    const scalarList& gb
) const
{
    const pointField& pts = mesh_.points();
    const labelListList& cellPts = mesh_.cellPoints();
    List<DynamicList<vector>> local(gauges_.size());
    forAll(cellPts, celli)
    {
        scalar a0 = GREAT, a1 = -GREAT;
        scalar b0 = GREAT, b1 = -GREAT;
        scalar z0 = GREAT, z1 = -GREAT;
        for (const label pi : cellPts[celli])
        {
            const scalar a = pts[pi] & e1;
            const scalar b = pts[pi] & e2;
            const scalar z = pts[pi] & ez_;
            a0 = min(a0, a); a1 = max(a1, a);
            b0 = min(b0, b); b1 = max(b1, b);
            z0 = min(z0, z); z1 = max(z1, z);
        }
        forAll(gauges_, gi)
        {
            if (ga[gi] >= a0 && ga[gi] < a1 && gb[gi] >= b0 && gb[gi] < b1)
            {
                local[gi].append(vector(z0, z1, celli));
            }
        }
    }
    return local;
}


void Foam::functionObjects::armourWaveGauges::keepLayers
(
    const label gi,
    DynamicList<vector>& local
)
{
    // Every rank's (z0, z1, cell), the whole column bottom up, identical on
    // every rank.
    List<List<vector>> all(Pstream::nProcs());
    all[Pstream::myProcNo()].transfer(local);
    Pstream::gatherList(all);
    Pstream::scatterList(all);
    DynamicList<FixedList<scalar, 4>> column;
    forAll(all, proci)
    {
        for (const vector& c : all[proci])
        {
            column.append
            (
                FixedList<scalar, 4>({c.x(), c.y(), scalar(proci), c.z()})
            );
        }
    }
    Foam::sort(column);

    // One cell per layer: a cell overlapping the one below it (a
    // non-layered mesh) would count its height twice, so it is left out.
    DynamicList<vector2D> kept;
    DynamicList<label> cells, slots;
    scalar top = -GREAT;
    for (const FixedList<scalar, 4>& c : column)
    {
        if (c[0] < top - tol_)
        {
            continue;
        }
        if (label(c[2]) == Pstream::myProcNo())
        {
            cells.append(label(c[3]));
            slots.append(kept.size());
        }
        kept.append(vector2D(c[0], c[1]));
        top = c[1];
    }
    if (kept.empty())
    {
        FatalErrorInFunction
            << "gauge " << gauges_[gi] << " of " << name()
            << " lies outside the mesh" << exit(FatalError);
    }
    columnZ_[gi].transfer(kept);
    localCells_[gi].transfer(cells);
    localSlots_[gi].transfer(slots);
}


Foam::functionObjects::armourWaveGauges::armourWaveGauges
(
    const word& name,
    const Time& runTime,
    const dictionary& dict
)
:
    fvMeshFunctionObject(name, runTime, dict),
    alphaName_("alpha.water"),
    gauges_(),
    columnZ_(),
    localCells_(),
    localSlots_(),
    tol_(0),
    ez_(0, 0, 1),
    file_()
{
    read(dict);
}


bool Foam::functionObjects::armourWaveGauges::read(const dictionary& dict)
{
    fvMeshFunctionObject::read(dict);
    alphaName_ = dict.getOrDefault<word>("alpha", "alpha.water");
    dict.readEntry("gauges", gauges_);
    findColumns();

    if (Pstream::master())
    {
        const fileName dir
        (
            mesh_.time().globalPath()/"postProcessing"/name()
           /mesh_.time().timeName(mesh_.time().startTime().value())
        );
        mkDir(dir);
        file_.reset(new OFstream(dir/"surfaceElevation.dat"));
        OFstream& os = file_.ref();
        os.precision(9);
        os  << "# free-surface height at gauges (" << alphaName_
            << " column integral)" << nl << "# time";
        forAll(gauges_, gi)
        {
            os  << tab << "z(" << gauges_[gi].x() << ' '
                << gauges_[gi].y() << ' ' << gauges_[gi].z() << ')';
        }
        os  << endl;
    }
    return true;
}


bool Foam::functionObjects::armourWaveGauges::execute()
{
    return true;
}


bool Foam::functionObjects::armourWaveGauges::write()
{
    const volScalarField& alpha =
        mesh_.lookupObject<volScalarField>(alphaName_);

    scalarList level(gauges_.size(), Zero);
    forAll(gauges_, gi)
    {
        const List<vector2D>& column = columnZ_[gi];
        scalarField a(column.size(), Zero);
        forAll(localCells_[gi], i)
        {
            a[localSlots_[gi][i]] =
                min(max(alpha[localCells_[gi][i]], scalar(0)), scalar(1));
        }
        Pstream::listCombineGather(a, plusEqOp<scalar>());
        Pstream::listCombineScatter(a);

        // Water fills the column from its lowest cell up. A gap between two
        // cells is a solid cut out of the mesh: it counts as under water when
        // the cell above it is at least half water (the solid is submerged),
        // else as above the surface.
        level[gi] = column[0].x();
        scalar top = column[0].x();
        forAll(column, i)
        {
            if (column[i].x() - top > tol_ && a[i] >= 0.5)
            {
                level[gi] += column[i].x() - top;
            }
            level[gi] += a[i]*(column[i].y() - column[i].x());
            top = column[i].y();
        }
    }

    if (Pstream::master() && file_.valid())
    {
        OFstream& os = file_.ref();
        os  << mesh_.time().value();
        forAll(level, gi)
        {
            os  << tab << level[gi];
        }
        os  << endl;
    }
    return true;
}
