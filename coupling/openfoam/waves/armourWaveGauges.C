/*---------------------------------------------------------------------------*\
    armour-fsi: free-surface wave gauges (armourWaveGauges.H)
\*---------------------------------------------------------------------------*/

#include "armourWaveGauges.H"
#include "addToRunTimeSelectionTable.H"
#include "gravityMeshObject.H"
#include "volFields.H"
#include "OSspecific.H"

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

    const pointField& pts = mesh_.points();
    const labelListList& cellPts = mesh_.cellPoints();

    columns_.setSize(gauges_.size());
    dz_.setSize(gauges_.size());
    zBottom_.setSize(gauges_.size());

    List<DynamicList<label>> cols(gauges_.size());
    List<DynamicList<scalar>> dzs(gauges_.size());
    scalarList zLow(gauges_.size(), GREAT);

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
            const scalar a = gauges_[gi] & e1;
            const scalar b = gauges_[gi] & e2;
            if (a >= a0 && a < a1 && b >= b0 && b < b1)
            {
                cols[gi].append(celli);
                dzs[gi].append(z1 - z0);
                zLow[gi] = min(zLow[gi], z0);
            }
        }
    }

    forAll(gauges_, gi)
    {
        columns_[gi].transfer(cols[gi]);
        dz_[gi].transfer(dzs[gi]);
        zBottom_[gi] = returnReduce(zLow[gi], minOp<scalar>());
        if (returnReduce(columns_[gi].size(), sumOp<label>()) == 0)
        {
            FatalErrorInFunction
                << "gauge " << gauges_[gi] << " of " << name()
                << " lies outside the mesh" << exit(FatalError);
        }
    }
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
    columns_(),
    dz_(),
    zBottom_(),
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
        scalar depth = 0;
        forAll(columns_[gi], i)
        {
            const scalar a = alpha[columns_[gi][i]];
            depth += min(max(a, scalar(0)), scalar(1))*dz_[gi][i];
        }
        level[gi] = zBottom_[gi] + returnReduce(depth, sumOp<scalar>());
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
