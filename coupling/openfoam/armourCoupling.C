/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourCoupling.H"

#include "addToRunTimeSelectionTable.H"
#include "fvMatrices.H"
#include "fvMesh.H"
#include "fvcGrad.H"
#include "fvcLaplacian.H"
#include "fvmSup.H"
#include "uniformDimensionedFields.H"

// The armour side: plain C++ and Eigen, no OpenFOAM type crosses these.
#include "body_recorder.h"
#include "clump.h"
#include "coupler.h"
#include "engine_registry.h"
#include "free_body_engine.h"
#include "liggghts_engine.h"
#include "scene.h"
#include "scene_setup.h"
#include "shapes.h"

#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <iomanip>
#include <string>
#include <vector>

// * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * * * //

namespace Foam
{
namespace fv
{
    defineTypeNameAndDebug(armourCoupling, 0);
    addToRunTimeSelectionTable(option, armourCoupling, dictionary);
}
}


// * * * * * * * * * * * * * * * * armour side  * * * * * * * * * * * * * * //

struct Foam::fv::armourCoupling::armourSide
{
    std::unique_ptr<armour::RigidBodyEngine> engine;
    std::unique_ptr<armour::Coupler> coupler;
    armour::CellSet cells;
    std::vector<std::string> names;

    //- Owning body per cell at the last mask update, -1 outside all bodies
    std::vector<int> body;

    //- Master only; optional with a scene
    std::ofstream csv;

    //- Master only, scene mode: bodies.h5 + bodies.xdmf
    std::unique_ptr<armour::BodyRecorder> recorder;

    //- Fluid time of the next record [s], and the interval between records
    double nextRecord = 0;
    double recordInterval = 0;

    //- Master only, scene mode: water volumes per record (fluid.csv)
    std::ofstream fluidCsv;

    //- Scene mode: units held, mask imposed once, no loads, no engine
    //  advance (the fluid.frozen benchmark reference)
    bool frozen = false;

    //- Wall seconds of this rank in the coupling's parts, and its steps
    double loadSeconds = 0;
    double demSeconds = 0;
    double maskSeconds = 0;
    long steps = 0;

    //- Master only, scene mode: where the timings go (coupling_times.json)
    std::string timesFile;

    //- Master only: whether every rank's engine replica had the master's
    //  state to the bit at every record so far, and the largest spread of
    //  a body's position over the ranks [m]
    bool replicasIdentical = true;
    double replicaSpread = 0;

    //- How the force density is computed: unknown until the first coupled
    //  step checks the face-by-face sum against fvc on this mesh
    enum class forceDensityMethod { unchecked, faceByFace, fvc };
    forceDensityMethod method = forceDensityMethod::unchecked;

    //- Force density per cell [N/m^3], zero outside the units' cells
    std::vector<Eigen::Vector3d> forceDensity;
};


// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

Eigen::Vector3d toEigen(const Foam::vector& v)
{
    return Eigen::Vector3d(v.x(), v.y(), v.z());
}

// f = -grad(p) + laplacian(muEff, U) on the whole mesh, as OpenFOAM's
// schemes give it: the reference, and the fallback where the face-by-face
// sum below does not reproduce it.
Foam::tmp<Foam::volVectorField> fvcForceDensity
(
    const Foam::volScalarField& p,
    const Foam::volScalarField& muEff,
    const Foam::volVectorField& U
)
{
    return -Foam::fvc::grad(p) + Foam::fvc::laplacian(muEff, U);
}


// f = -grad(p) + laplacian(muEff, U) in the listed cells only, face by
// face: Gauss linear gradient, Gauss linear laplacian with the uncorrected
// surface-normal gradient. On a 100-unit tank the whole-mesh fvc expression
// took ~90 % of the load time, mostly in cells no unit touches. Exact for
// what fvc computes with the default schemes on an orthogonal mesh (there
// the non-orthogonal correction vanishes); forceDensityAgrees() checks
// that on the mesh at hand before it is used.
void faceByFaceForceDensity
(
    const Foam::fvMesh& mesh,
    const Foam::volScalarField& p,
    const Foam::volScalarField& muEff,
    const Foam::volVectorField& U,
    const Foam::labelUList& cells,
    Foam::vectorField& f
)
{
    using namespace Foam;
    const labelUList& own = mesh.owner();
    const labelUList& nei = mesh.neighbour();
    const surfaceScalarField& w = mesh.weights();
    const surfaceScalarField& dc = mesh.nonOrthDeltaCoeffs();
    const surfaceVectorField& Sf = mesh.Sf();
    const surfaceScalarField& magSf = mesh.magSf();
    const label nInternal = mesh.nInternalFaces();
    const polyBoundaryMesh& patches = mesh.boundaryMesh();

    // Face values on each patch, as fvc takes them: the boundary value, or
    // the weighted mean with the neighbour across a coupled patch.
    PtrList<scalarField> pFace(patches.size());
    PtrList<scalarField> muFace(patches.size());
    PtrList<vectorField> snGradU(patches.size());
    forAll(patches, pi)
    {
        const fvPatchScalarField& pb = p.boundaryField()[pi];
        const fvPatchScalarField& mub = muEff.boundaryField()[pi];
        const fvPatchVectorField& Ub = U.boundaryField()[pi];
        if (pb.coupled())
        {
            const scalarField& wp = w.boundaryField()[pi];
            pFace.set
            (
                pi,
                new scalarField
                (
                    wp*pb.patchInternalField() + (1.0 - wp)*pb.patchNeighbourField()
                )
            );
            muFace.set
            (
                pi,
                new scalarField
                (
                    wp*mub.patchInternalField() + (1.0 - wp)*mub.patchNeighbourField()
                )
            );
            snGradU.set(pi, new vectorField(Ub.snGrad(dc.boundaryField()[pi])));
        }
        else
        {
            pFace.set(pi, new scalarField(pb));
            muFace.set(pi, new scalarField(mub));
            snGradU.set(pi, new vectorField(Ub.snGrad()));
        }
    }

    const cellList& cellFaces = mesh.cells();
    const scalarField& V = mesh.V();
    forAll(cells, k)
    {
        const label c = cells[k];
        vector pressure = Zero;
        vector viscous = Zero;
        for (const label face : cellFaces[c])
        {
            if (face < nInternal)
            {
                const label o = own[face];
                const label n = nei[face];
                const scalar sign = (o == c) ? 1.0 : -1.0;
                const scalar wf = w[face];
                pressure += sign*Sf[face]*(wf*p[o] + (1.0 - wf)*p[n]);
                viscous +=
                    sign*(wf*muEff[o] + (1.0 - wf)*muEff[n])*magSf[face]
                   *dc[face]*(U[n] - U[o]);
                continue;
            }
            const label pi = patches.whichPatch(face);
            const label i = face - patches[pi].start();
            if (i >= Sf.boundaryField()[pi].size())
            {
                continue; // empty patch: no flux through it
            }
            pressure += Sf.boundaryField()[pi][i]*pFace[pi][i];
            viscous += muFace[pi][i]*magSf.boundaryField()[pi][i]*snGradU[pi][i];
        }
        f[k] = (viscous - pressure)/V[c];
    }
}


// The face-by-face force density against fvc's, on smooth non-linear test
// fields (the real ones may be at rest at the first step) with the real
// mu_eff, in every cell of every rank: true when they agree to rounding.
bool forceDensityAgrees(const Foam::fvMesh& mesh, const Foam::volScalarField& muEff)
{
    using namespace Foam;
    const IOobject io
    (
        "armourCheck",
        mesh.time().timeName(),
        mesh,
        IOobject::NO_READ,
        IOobject::NO_WRITE,
        false
    );
    volScalarField p
    (
        IOobject(io, "armourCheckP"),
        mesh,
        dimensionedScalar(dimPressure, Zero),
        "calculated"
    );
    volVectorField U
    (
        IOobject(io, "armourCheckU"),
        mesh,
        dimensionedVector(dimVelocity, Zero),
        "calculated"
    );
    const auto pOf = [](const vector& x)
    {
        return 1e4*(1.0 + x.x()*x.x() + 0.5*x.y()*x.z() + std::sin(3.0*x.z()));
    };
    const auto UOf = [](const vector& x)
    {
        return vector
        (
            std::sin(2.0*x.y()) + x.z()*x.z(),
            x.x()*x.z() - std::cos(x.x()),
            x.x()*x.x()*x.y() + 0.3*x.z()
        );
    };
    forAll(mesh.C(), i)
    {
        p[i] = pOf(mesh.C()[i]);
        U[i] = UOf(mesh.C()[i]);
    }
    forAll(mesh.boundary(), pi)
    {
        if (p.boundaryField()[pi].coupled())
        {
            continue;
        }
        const vectorField& Cf = mesh.C().boundaryField()[pi];
        forAll(Cf, i)
        {
            p.boundaryFieldRef()[pi][i] = pOf(Cf[i]);
            U.boundaryFieldRef()[pi][i] = UOf(Cf[i]);
        }
    }
    p.correctBoundaryConditions();
    U.correctBoundaryConditions();

    const volVectorField reference(fvcForceDensity(p, muEff, U));
    labelList all(mesh.nCells());
    forAll(all, i)
    {
        all[i] = i;
    }
    vectorField f(mesh.nCells());
    faceByFaceForceDensity(mesh, p, muEff, U, all, f);
    const scalar scale = returnReduce(gMax(mag(reference.primitiveField())), maxOp<scalar>());
    const scalar difference = returnReduce(gMax(mag(f - reference.primitiveField())), maxOp<scalar>());
    return difference <= 1e-9*scale;
}


// This rank's cells for the coupler; copied once: the mesh is static.
armour::CellSet cellSet(const Foam::fvMesh& mesh)
{
    armour::CellSet cells;
    const Foam::vectorField& C = mesh.C();
    const Foam::scalarField& V = mesh.V();
    cells.centres.resize(C.size());
    cells.volumes.resize(C.size());
    forAll(C, i)
    {
        cells.centres[i] = toEigen(C[i]);
        cells.volumes[i] = V[i];
    }
    return cells;
}


Foam::vector toFoam(const Eigen::Vector3d& v)
{
    return Foam::vector(v.x(), v.y(), v.z());
}

// Axis words (x y z) -> held flags; anything else is a user error worth
// stopping for, because a silently free axis changes the experiment.
std::array<bool, 3> readAxes
(
    const Foam::dictionary& dict,
    const Foam::word& key
)
{
    std::array<bool, 3> held{{false, false, false}};
    if (!dict.found(key))
    {
        return held;
    }
    const Foam::wordList axes(dict.lookup(key));
    for (const Foam::word& a : axes)
    {
        if (a == "x") held[0] = true;
        else if (a == "y") held[1] = true;
        else if (a == "z") held[2] = true;
        else
        {
            FatalIOErrorInFunction(dict)
                << key << ": unknown axis '" << a << "' (use x, y, z)"
                << Foam::exit(Foam::FatalIOError);
        }
    }
    return held;
}

armour::UnitTemplate readUnit
(
    const Foam::word& name,
    const Foam::dictionary& dict,
    bool needClump
)
{
    const Foam::word shapeName(dict.lookup("shape"));
    const Foam::scalar size = dict.get<Foam::scalar>("size");
    const Foam::scalar density = dict.get<Foam::scalar>("density");

    armour::Shape shape;
    if (shapeName == "cube")
    {
        shape = armour::make_cube_shape
        (
            size,
            dict.lookupOrDefault<Foam::scalar>("chamfer", 0),
            density
        );
    }
    else if (shapeName == "dolos")
    {
        shape = armour::make_dolos_shape
        (
            size,
            dict.lookupOrDefault<Foam::scalar>
            (
                "waist",
                armour::kDolosWaistDefault
            ),
            density
        );
    }
    else
    {
        FatalIOErrorInFunction(dict)
            << "body " << name << ": unknown shape '" << shapeName
            << "' (use cube or dolos)" << Foam::exit(Foam::FatalIOError);
    }

    armour::UnitTemplate unit;
    unit.name = name;
    unit.mesh = shape.mesh;
    unit.props = shape.props;
    if (needClump)
    {
        const Foam::label n = dict.get<Foam::label>("spheres");
        unit.clump =
            armour::build_clump(shape, armour::ClumpMethod::optimised, n);
    }
    return unit;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

Foam::fv::armourCoupling::armourCoupling
(
    const word& name,
    const word& modelType,
    const dictionary& dict,
    const fvMesh& mesh
)
:
    option(name, modelType, dict, mesh),
    armour_(new armourSide),
    penalty_(coeffs_.lookupOrDefault<scalar>("penalty", 0)),
    chi_
    (
        IOobject
        (
            "armourChi",
            mesh.time().timeName(),
            mesh,
            IOobject::NO_READ,
            IOobject::AUTO_WRITE
        ),
        mesh,
        dimensionedScalar(dimless, Zero)
    ),
    UBody_
    (
        IOobject
        (
            "armourUBody",
            mesh.time().timeName(),
            mesh,
            IOobject::NO_READ,
            IOobject::AUTO_WRITE
        ),
        mesh,
        dimensionedVector(dimVelocity, Zero)
    ),
    lastTimeIndex_(mesh.time().timeIndex())
{
    fieldNames_ = wordList(1, "U");
    applied_.setSize(fieldNames_.size(), false);

    if (coeffs_.found("scene"))
    {
        constructFromScene(fileName(coeffs_.get<fileName>("scene")));
        return;
    }

    if (penalty_ <= 0)
    {
        FatalIOErrorInFunction(coeffs_)
            << "penalty must be > 0 (1/s), got " << penalty_
            << exit(FatalIOError);
    }

    const word engineName(coeffs_.lookup("engine"));
    const word maskName(coeffs_.lookupOrDefault<word>("mask", "exact"));
    if (engineName != "free_body" && engineName != "liggghts")
    {
        FatalIOErrorInFunction(coeffs_)
            << "unknown engine '" << engineName
            << "' (use free_body or liggghts)" << exit(FatalIOError);
    }
    if (maskName != "exact" && maskName != "spheres")
    {
        FatalIOErrorInFunction(coeffs_)
            << "unknown mask '" << maskName << "' (use exact or spheres)"
            << exit(FatalIOError);
    }
    const bool needClump = engineName == "liggghts" || maskName == "spheres";

    // The solver's gravity, so the engine and the fluid agree on it.
    Eigen::Vector3d gravity(0, 0, -9.81);
    if (mesh.time().foundObject<uniformDimensionedVectorField>("g"))
    {
        gravity = toEigen
        (
            mesh.time().lookupObject<uniformDimensionedVectorField>("g")
           .value()
        );
    }
    else if (coeffs_.found("gravity"))
    {
        gravity = toEigen(coeffs_.get<vector>("gravity"));
    }

    try
    {
        armour::EngineSettings settings;
        settings.gravity = gravity;
        settings.time_step =
            coeffs_.lookupOrDefault<scalar>("engineTimeStep", 0);
        settings.materials = {armour::Material{}};
        settings.materials[0].name = "armour";
        // The engine's domain is the fluid domain, padded so bodies touching
        // the walls stay inside it.
        const boundBox& bb = mesh.bounds();
        const Eigen::Vector3d pad = Eigen::Vector3d::Constant(0.1*bb.mag());
        settings.domain_min = toEigen(bb.min()) - pad;
        settings.domain_max = toEigen(bb.max()) + pad;
        settings.work_dir = mesh.time().globalPath()/"armourEngine";

        armour_->engine =
            engineName == "liggghts"
          ? armour::make_liggghts_engine(settings)
          : armour::make_free_body_engine(settings);

        std::vector<armour::UnitTemplate> units;
        std::vector<int> bodyUnit;
        const dictionary& bodies = coeffs_.subDict("bodies");
        for (const entry& e : bodies)
        {
            if (!e.isDict())
            {
                continue;
            }
            const dictionary& bd = e.dict();
            units.push_back(readUnit(e.keyword(), bd, needClump));
            const int unit = armour_->engine->add_template(units.back());

            armour::BodyInit init;
            init.unit = unit;
            init.pose.position = toEigen(bd.get<vector>("position"));
            if (bd.found("orientation"))
            {
                const scalarList q(bd.lookup("orientation"));
                if (q.size() != 4)
                {
                    FatalIOErrorInFunction(bd)
                        << "orientation: 4 numbers (w x y z) expected"
                        << exit(FatalIOError);
                }
                init.pose.orientation =
                    Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
            }
            init.velocity =
                toEigen(bd.lookupOrDefault<vector>("velocity", Zero));
            init.angular_velocity =
                toEigen(bd.lookupOrDefault<vector>("angularVelocity", Zero));
            init.fixed_translation = readAxes(bd, "fixedTranslation");
            init.fixed_rotation = readAxes(bd, "fixedRotation");
            if (bd.found("pivot"))
            {
                init.pivot = toEigen(bd.get<vector>("pivot"));
            }

            bodyUnit.push_back(armour_->engine->add_body(init));
            // One template per body: body k uses unit k.
            bodyUnit.back() = unit;
            armour_->names.push_back(e.keyword());
        }
        if (units.empty())
        {
            FatalIOErrorInFunction(bodies)
                << "no bodies" << exit(FatalIOError);
        }

        armour::CouplerSettings cs;
        cs.mask =
            maskName == "spheres"
          ? armour::MaskSource::clump_spheres
          : armour::MaskSource::exact_shape;
        cs.smoothing_cells =
            coeffs_.lookupOrDefault<scalar>("smoothingCells", 1);
        cs.fluid_density =
            coeffs_.lookupOrDefault<scalar>("fluidDensity", 1000);
        cs.added_mass_coefficient =
            coeffs_.lookupOrDefault<scalar>("addedMass", 0);
        cs.gravity = gravity;

        armour_->coupler.reset
        (
            new armour::Coupler
            (
                *armour_->engine,
                std::move(units),
                std::move(bodyUnit),
                cs
            )
        );

        armour_->cells = cellSet(mesh);
        updateFields();
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "armour: " << err.what() << exit(FatalError);
    }

    if (Pstream::master())
    {
        openCsv
        (
            mesh.time().globalPath()
           /coeffs_.lookupOrDefault<fileName>("csv", "armourBodies.csv")
        );
    }

    Info<< "    armourCoupling: " << armour_->names.size() << " bodies, engine "
        << engineName << ", mask " << maskName << ", K = " << penalty_
        << " 1/s, g = " << toFoam(gravity) << endl;
}


Foam::fv::armourCoupling::~armourCoupling()
{}


// * * * * * * * * * * * * * * * Private Functions * * * * * * * * * * * * * //

void Foam::fv::armourCoupling::constructFromScene(const fileName& scenePath)
{
    const Time& runTime = mesh_.time();
    std::string engineName;
    try
    {
        // Every rank reads the same resolved scene and builds the same
        // engine: identical replicas fed with the same summed loads.
        const armour::Scene scene = armour::load_scene(scenePath);
        if (!scene.fluid)
        {
            FatalIOErrorInFunction(coeffs_)
                << "scene " << scenePath << " has no [fluid] table"
                << exit(FatalIOError);
        }
        const armour::SceneFluid& fluid = *scene.fluid;
        penalty_ = fluid.penalty;
        engineName = scene.engine;
        armour_->frozen = fluid.frozen;

        // The fluid and the engine must feel the same gravity.
        const Eigen::Vector3d gravity = toEigen
        (
            runTime.lookupObject<uniformDimensionedVectorField>("g").value()
        );
        if ((gravity - scene.gravity).norm() > 1e-9*scene.gravity.norm())
        {
            FatalIOErrorInFunction(coeffs_)
                << "constant/g " << toFoam(gravity)
                << " differs from the scene's run.gravity "
                << toFoam(scene.gravity) << exit(FatalIOError);
        }

        const std::string cache =
            coeffs_.lookupOrDefault<fileName>
            (
                "cache",
                fileName(armour::default_cache_dir())
            );
        armour::SceneSetup setup = armour::build_scene(scene, cache, false);
        setup.settings.work_dir = runTime.globalPath()/"armourEngine";
        armour_->engine = armour::make_engine(scene.engine, setup.settings);
        for (const armour::UnitTemplate& u : setup.units)
        {
            armour_->engine->add_template(u);
        }
        for (const armour::Wall& w : setup.walls)
        {
            armour_->engine->add_wall(w);
        }
        std::vector<int> bodyUnit;
        for (const armour::BodyInit& b : setup.bodies)
        {
            armour_->engine->add_body(b);
            bodyUnit.push_back(b.unit);
            armour_->names.push_back
            (
                setup.units[b.unit].name + "_"
              + std::to_string(armour_->names.size())
            );
        }

        armour::CouplerSettings cs;
        cs.mask =
            fluid.mask == "spheres"
          ? armour::MaskSource::clump_spheres
          : armour::MaskSource::exact_shape;
        cs.smoothing_cells = fluid.smoothing_cells;
        cs.fluid_density = fluid.fluid_density;
        cs.added_mass_coefficient = fluid.added_mass;
        cs.gravity = gravity;

        std::vector<armour::RecorderUnit> recorderUnits;
        for (const armour::UnitTemplate& u : setup.units)
        {
            recorderUnits.push_back({u.name, u.mesh});
        }
        armour_->coupler.reset
        (
            new armour::Coupler(*armour_->engine, setup.units, bodyUnit, cs)
        );

        armour_->cells = cellSet(mesh_);
        updateFields();

        // The record sits beside the scene it ran (the run's output
        // folder), unless the dictionary names another folder.
        if (Pstream::master())
        {
            const fileName outDir =
                coeffs_.lookupOrDefault<fileName>("output", scenePath.path());
            const armour::TimeStepReport dt =
                armour_->engine->time_step_report();
            armour_->recorder.reset
            (
                new armour::BodyRecorder
                (
                    outDir/"bodies.h5",
                    outDir/"bodies.xdmf",
                    recorderUnits,
                    bodyUnit,
                    {
                        {"scene", scene.name},
                        {"engine", armour_->engine->name()},
                        {"dt", std::to_string(dt.used)},
                        {"coupling", "interFoam armourCoupling"},
                        {"external_force", "fluid load F (without gravity)"}
                    }
                )
            );
            std::vector<armour::BodyState> states;
            for (int k = 0; k < armour_->engine->body_count(); ++k)
            {
                states.push_back(armour_->engine->state(k));
                states.back().external_force.setZero();
                states.back().external_torque.setZero();
            }
            armour_->recorder->append(runTime.value(), states);

            // The free surface a floating unit settles against moves with
            // the water it displaces and with what seeps into its ramp
            // cells; the water volume outside the units pins it down.
            armour_->timesFile = outDir/"coupling_times.json";
            armour_->fluidCsv.open(outDir/"fluid.csv");
            armour_->fluidCsv
                << "time,water_volume,water_volume_outside_units\n"
                << std::setprecision(12);
        }
        // On every rank: the record times decide collective reductions.
        armour_->recordInterval = scene.output_interval;
        armour_->nextRecord = runTime.value() + scene.output_interval;
    }
    catch (const std::exception& err)
    {
        FatalErrorInFunction
            << "armour: " << err.what() << exit(FatalError);
    }

    if (Pstream::master() && coeffs_.found("csv"))
    {
        openCsv(runTime.globalPath()/coeffs_.get<fileName>("csv"));
    }

    Info<< "    armourCoupling: scene " << scenePath << ", "
        << armour_->names.size() << " bodies, engine " << engineName
        << ", K = " << penalty_ << " 1/s"
        << (armour_->frozen ? ", frozen (mask only)" : "") << endl;
}


void Foam::fv::armourCoupling::openCsv(const fileName& csvName)
{
    armour_->csv.open(csvName);
    if (!armour_->csv)
    {
        FatalErrorInFunction
            << "cannot write " << csvName << exit(FatalError);
    }
    armour_->csv
        << "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,"
           "Fx,Fy,Fz,Mx,My,Mz,Sx,Sy,Sz,chiVolume,engineTime\n";
    armour_->csv << std::setprecision(10);
}


void Foam::fv::armourCoupling::updateFields()
{
    const armour::CellMask& mask = armour_->coupler->update_mask(armour_->cells);
    scalarField& chi = chi_.primitiveFieldRef();
    vectorField& Ub = UBody_.primitiveFieldRef();
    forAll(chi, i)
    {
        chi[i] = mask.chi[i];
        Ub[i] = toFoam(mask.velocity[i]);
    }
    armour_->body = mask.body;
    chi_.correctBoundaryConditions();
    UBody_.correctBoundaryConditions();
}


void Foam::fv::armourCoupling::couple
(
    const volScalarField& rho,
    const volVectorField& U
)
{
    const Time& runTime = mesh_.time();
    using clock = std::chrono::steady_clock;
    const auto seconds = [](clock::time_point a, clock::time_point b)
    {
        return std::chrono::duration<double>(b - a).count();
    };
    const clock::time_point t0 = clock::now();
    const label nb = armour_->names.size();
    ++armour_->steps;
    List<scalar> buf(10*nb, Zero);
    if (!armour_->frozen)
    {
        const volScalarField& p = mesh_.lookupObject<volScalarField>("p");

        // mu_eff = rho (nu + nut); nut only where a turbulence model made one.
        volScalarField muEff
        (
            "armourMuEff",
            rho*mesh_.lookupObject<volScalarField>("nu")
        );
        if (mesh_.foundObject<volScalarField>("nut"))
        {
            muEff += rho*mesh_.lookupObject<volScalarField>("nut");
        }
        using method = armourSide::forceDensityMethod;
        if (armour_->method == method::unchecked)
        {
            const bool agrees = forceDensityAgrees(mesh_, muEff);
            armour_->method = agrees ? method::faceByFace : method::fvc;
            Info<< "    armourCoupling: force density "
                << (agrees
                    ? "face by face in the units' cells (checked against fvc)"
                    : "by fvc on the whole mesh (the face-by-face sum differs "
                      "from fvc here: non-orthogonal mesh or other schemes)")
                << endl;
        }
        std::vector<Eigen::Vector3d>& fd = armour_->forceDensity;
        fd.assign(mesh_.nCells(), Eigen::Vector3d::Zero());
        if (armour_->method == method::faceByFace)
        {
            DynamicList<label> cells(mesh_.nCells()/8);
            forAll(armour_->body, i)
            {
                if (armour_->body[i] >= 0)
                {
                    cells.append(i);
                }
            }
            vectorField f(cells.size());
            faceByFaceForceDensity(mesh_, p, muEff, U, cells, f);
            forAll(cells, k)
            {
                fd[cells[k]] = toEigen(f[k]);
            }
        }
        else
        {
            const volVectorField f(fvcForceDensity(p, muEff, U));
            forAll(f, i)
            {
                fd[i] = toEigen(f[i]);
            }
        }

        armour::BodyLoads loads;
        try
        {
            loads = armour_->coupler->integrate_loads(armour_->cells, fd);
        }
        catch (const std::exception& err)
        {
            FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
        }

        // The momentum source each body puts into the fluid, at the same fields:
        // with the loads, it checks the coupling's force balance.
        forAll(U, i)
        {
            const label k = armour_->body[i];
            if (k < 0)
            {
                continue;
            }
            const vector S =
                -rho[i]*penalty_*chi_[i]*(U[i] - UBody_[i])*mesh_.V()[i];
            for (direction c = 0; c < 3; ++c)
            {
                buf[10*k + 6 + c] += S[c];
            }
            buf[10*k + 9] += chi_[i]*mesh_.V()[i];
        }
        // The mask's volume and first moment travel with the loads: the
        // torque is taken about the mask's centroid once they are summed.
        List<scalar> mask(4*nb, Zero);
        for (label k = 0; k < nb; ++k)
        {
            for (direction c = 0; c < 3; ++c)
            {
                buf[10*k + c] = loads.force[k][c];
                buf[10*k + 3 + c] = loads.torque[k][c];
                mask[4*k + c] = loads.mask_first_moment[k][c];
            }
            mask[4*k + 3] = loads.mask_volume[k];
        }
        // Every rank gets the same totals, so every rank's engine replica
        // (free_body, bullet, or a serial LIGGGHTS per rank) takes the same
        // step.
        Pstream::listCombineGather(buf, plusEqOp<scalar>());
        Pstream::listCombineScatter(buf);
        Pstream::listCombineGather(mask, plusEqOp<scalar>());
        Pstream::listCombineScatter(mask);
        for (label k = 0; k < nb; ++k)
        {
            for (direction c = 0; c < 3; ++c)
            {
                loads.force[k][c] = buf[10*k + c];
                loads.torque[k][c] = buf[10*k + 3 + c];
                loads.mask_first_moment[k][c] = mask[4*k + c];
            }
            loads.mask_volume[k] = mask[4*k + 3];
        }
        armour::centre_torque_on_mask(loads);
        // What is recorded is what is applied.
        for (label k = 0; k < nb; ++k)
        {
            for (direction c = 0; c < 3; ++c)
            {
                buf[10*k + 3 + c] = loads.torque[k][c];
            }
        }

        const clock::time_point t1 = clock::now();
        try
        {
            armour_->coupler->advance(loads, runTime.deltaTValue());
            const clock::time_point t2 = clock::now();
            updateFields();
            armour_->loadSeconds += seconds(t0, t1);
            armour_->demSeconds += seconds(t1, t2);
            armour_->maskSeconds += seconds(t2, clock::now());
        }
        catch (const std::exception& err)
        {
            FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
        }
    }

    // Every record interval and at the last step, so the record ends where
    // the run does.
    const double t = runTime.value();
    const double dtF = runTime.deltaTValue();
    const bool recordNow =
        armour_->recordInterval > 0
     && (
            t >= armour_->nextRecord - 1e-6*dtF
         || t + 0.5*dtF >= runTime.endTime().value()
        );
    scalar water = 0;
    scalar waterOutside = 0;
    if (recordNow)
    {
        if (mesh_.foundObject<volScalarField>("alpha.water"))
        {
            const volScalarField& alpha =
                mesh_.lookupObject<volScalarField>("alpha.water");
            forAll(alpha, i)
            {
                water += alpha[i]*mesh_.V()[i];
                waterOutside += alpha[i]*(1 - chi_[i])*mesh_.V()[i];
            }
        }
        reduce(water, sumOp<scalar>());
        reduce(waterOutside, sumOp<scalar>());
        while (armour_->nextRecord <= t + 1e-6*dtF)
        {
            armour_->nextRecord += armour_->recordInterval;
        }
    }
    if (recordNow && Pstream::parRun())
    {
        // The replicas only stay one run if the engine is deterministic
        // (same summed loads in, same bits out); a rank that drifted would
        // put its bodies elsewhere in its own cells. Checked at each record:
        // the spread of every state component over the ranks.
        List<scalar> hi(13*nb, Zero);
        for (label k = 0; k < nb; ++k)
        {
            const armour::BodyState s = armour_->engine->state(k);
            const Eigen::Quaterniond& q = s.pose.orientation;
            const scalar state[13] =
            {
                s.pose.position.x(), s.pose.position.y(), s.pose.position.z(),
                q.w(), q.x(), q.y(), q.z(),
                s.velocity.x(), s.velocity.y(), s.velocity.z(),
                s.angular_velocity.x(), s.angular_velocity.y(),
                s.angular_velocity.z()
            };
            for (label c = 0; c < 13; ++c)
            {
                hi[13*k + c] = state[c];
            }
        }
        List<scalar> lo(hi);
        Pstream::listCombineGather(hi, maxEqOp<scalar>());
        Pstream::listCombineGather(lo, minEqOp<scalar>());
        if (Pstream::master())
        {
            const bool wasIdentical = armour_->replicasIdentical;
            forAll(hi, i)
            {
                if (!(hi[i] == lo[i]))
                {
                    armour_->replicasIdentical = false;
                }
                if (i % 13 < 3)
                {
                    armour_->replicaSpread =
                        max(armour_->replicaSpread, hi[i] - lo[i]);
                }
            }
            if (wasIdentical && !armour_->replicasIdentical)
            {
                WarningInFunction
                    << "armour: the ranks' engine replicas differ at t = "
                    << t << " s (positions by up to " << armour_->replicaSpread
                    << " m), so the ranks no longer run one simulation (an"
                    << " engine that is not deterministic?); the record is the"
                    << " master rank's" << endl;
            }
        }
    }
    if (recordNow && armour_->recorder)
    {
        std::vector<armour::BodyState> states;
        for (label k = 0; k < nb; ++k)
        {
            states.push_back(armour_->engine->state(k));
            states.back().external_force =
                Eigen::Vector3d(buf[10*k], buf[10*k + 1], buf[10*k + 2]);
            states.back().external_torque =
                Eigen::Vector3d(buf[10*k + 3], buf[10*k + 4], buf[10*k + 5]);
        }
        try
        {
            armour_->recorder->append(t, states);
        }
        catch (const std::exception& err)
        {
            FatalErrorInFunction << "armour: " << err.what() << exit(FatalError);
        }
        armour_->fluidCsv
            << t << ',' << water << ',' << waterOutside << std::endl;
        std::ofstream times(armour_->timesFile);
        times
            << std::setprecision(9)
            << "{\"frozen\": " << (armour_->frozen ? "true" : "false")
            << ", \"coupling_steps\": " << armour_->steps
            << ", \"load_seconds\": " << armour_->loadSeconds
            << ", \"dem_seconds\": " << armour_->demSeconds
            << ", \"mask_seconds\": " << armour_->maskSeconds
            << ", \"replicas_identical\": "
            << (armour_->replicasIdentical ? "true" : "false")
            << ", \"replica_position_spread\": " << armour_->replicaSpread
            // Both clocks start at 0 (the cases' startTime); the engine keeps
            // the fluid's to half an engine step (frozen runs never advance).
            << std::setprecision(17)
            << ", \"fluid_time\": " << t
            << ", \"engine_time\": " << armour_->engine->time()
            << ", \"engine_time_step\": " << armour_->engine->time_step()
            << "}\n";
    }

    if (Pstream::master() && armour_->csv.is_open())
    {
        std::ofstream& out = armour_->csv;
        for (label k = 0; k < nb; ++k)
        {
            const armour::BodyState s = armour_->engine->state(k);
            const Eigen::Quaterniond& q = s.pose.orientation;
            out << runTime.value() << ',' << armour_->names[k] << ','
                << s.pose.position.x() << ',' << s.pose.position.y() << ','
                << s.pose.position.z() << ','
                << q.w() << ',' << q.x() << ',' << q.y() << ',' << q.z() << ','
                << s.velocity.x() << ',' << s.velocity.y() << ','
                << s.velocity.z() << ','
                << s.angular_velocity.x() << ',' << s.angular_velocity.y()
                << ',' << s.angular_velocity.z();
            for (label c = 0; c < 10; ++c)
            {
                out << ',' << buf[10*k + c];
            }
            out << ',' << armour_->engine->time() << '\n';
        }
        out.flush();
    }

    if (log)
    {
        for (label k = 0; k < nb; ++k)
        {
            Info<< "    armour " << armour_->names[k] << ": F = ("
                << buf[10*k] << ' ' << buf[10*k + 1] << ' ' << buf[10*k + 2]
                << ") N, S = (" << buf[10*k + 6] << ' ' << buf[10*k + 7]
                << ' ' << buf[10*k + 8] << ") N" << endl;
        }
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void Foam::fv::armourCoupling::addSup
(
    const volScalarField& rho,
    fvMatrix<vector>& eqn,
    const label fieldi
)
{
    const volVectorField& U = eqn.psi();

    // Once per time step, not per PIMPLE outer corrector: the engine must
    // take exactly one step of deltaT.
    if (mesh_.time().timeIndex() != lastTimeIndex_)
    {
        lastTimeIndex_ = mesh_.time().timeIndex();
        couple(rho, U);
    }

    const volScalarField rhoKchi
    (
        "armourRhoKchi",
        rho*dimensionedScalar("K", inv(dimTime), penalty_)*chi_
    );
    eqn -= fvm::Sp(rhoKchi, U);
    eqn += rhoKchi*UBody_;
}


bool Foam::fv::armourCoupling::read(const dictionary& dict)
{
    if (option::read(dict))
    {
        coeffs_.readIfPresent("penalty", penalty_);
        return true;
    }
    return false;
}


// ************************************************************************* //
