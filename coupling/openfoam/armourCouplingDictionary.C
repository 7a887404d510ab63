// The stand-alone dictionary front end of armourCoupling (legacy: bodies
// written by hand in fvOptions, without a scene; armourCoupling.H lists its
// entries). `armour run` uses the scene front end; this one is kept for the
// hand-written cases in foam_cases/buoyancy_cube and floating_box.
#include "armourCouplingSide.H"
#include "armourForceDensity.H"

#include "uniformDimensionedFields.H"

#include "clump.h"
#include "engine_registry.h"
#include "shapes.h"

#include <array>
#include <exception>

using namespace Foam::armourFoam;

namespace
{

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


void Foam::fv::armourCoupling::constructFromDictionary()
{
    const fvMesh& mesh = mesh_;
    if (penalty_ <= 0)
    {
        FatalIOErrorInFunction(coeffs_)
            << "penalty must be > 0 (1/s), got " << penalty_
            << exit(FatalIOError);
    }

    const word engineName(coeffs_.lookup("engine"));
    const word maskName(coeffs_.lookupOrDefault<word>("mask", "exact"));
    const armour::EngineStyle* style = nullptr;
    try
    {
        style = &armour::engine_style(engineName);
    }
    catch (const std::exception& err)
    {
        FatalIOErrorInFunction(coeffs_) << err.what() << exit(FatalIOError);
    }
    if (maskName != "exact" && maskName != "spheres")
    {
        FatalIOErrorInFunction(coeffs_)
            << "unknown mask '" << maskName << "' (use exact or spheres)"
            << exit(FatalIOError);
    }
    const bool needClump =
        style->capabilities.shape == armour::ShapeModel::sphere_clumps
     || maskName == "spheres";

    // The solver's gravity, so the engine and the fluid agree on it.
    Eigen::Vector3d gravity(0, 0, -armour::kStandardGravity);
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

        armour_->engine = style->make(settings);

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
            coeffs_.lookupOrDefault<scalar>("fluidDensity", armour::kFreshWaterDensity);
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
