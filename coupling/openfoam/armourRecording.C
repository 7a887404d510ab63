/*---------------------------------------------------------------------------*\
    armour-fsi: two-way coupling of armour units with interFoam
\*---------------------------------------------------------------------------*/

#include "armourRecording.H"

#include <cstdlib>
#include <iomanip>
#include <sstream>
#include <vector>

// * * * * * * * * * * * * * * * Local Functions * * * * * * * * * * * * * * //

namespace
{

// A CSV whose first column is time: keeps the header and the rows up to t
// (a resumed run writes the later ones again).
void keepRowsUpTo(const std::string& path, double t)
{
    std::ifstream in(path);
    std::vector<std::string> kept;
    std::string line;
    for (bool header = true; std::getline(in, line); header = false)
    {
        if (header || std::strtod(line.c_str(), nullptr) <= t)
        {
            kept.push_back(line);
        }
    }
    in.close();
    std::ofstream out(path, std::ios::trunc);
    for (const std::string& row : kept)
    {
        out << row << '\n';
    }
}

} // End anonymous namespace

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

armourFoam::recording::recording(const Foam::Time& runTime, double interval)
:
    nextRecord_(runTime.value() + interval),
    interval_(interval)
{}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void armourFoam::recording::open
(
    const std::string& outDir,
    const std::string& sceneName,
    const bodyExchange& bodies,
    double t,
    bool compress
)
{
    const armour::RigidBodyEngine& engine = bodies.engine();
    std::vector<armour::RecorderUnit> units;
    for (const armour::UnitTemplate& u : bodies.units())
    {
        units.push_back({u.name, u.mesh});
    }
    bodies_.reset
    (
        new armour::BodyRecorder
        (
            outDir + "/bodies.h5",
            outDir + "/bodies.xdmf",
            units,
            bodies.bodyUnit(),
            {
                {"scene", sceneName},
                {"engine", engine.name()},
                {"dt", std::to_string(engine.time_step_report().used)},
                {"coupling", "interFoam armourCoupling"},
                {"external_force", "fluid load F (without gravity)"}
            },
            compress
        )
    );
    std::vector<armour::BodyState> states;
    for (int k = 0; k < engine.body_count(); ++k)
    {
        states.push_back(engine.state(k));
        states.back().external_force.setZero();
        states.back().external_torque.setZero();
    }
    bodies_->append(t, states);

    // The free surface a floating unit settles against moves with the water
    // it displaces and with what seeps into its ramp cells; the water volume
    // outside the units pins it down.
    timesFile_ = outDir + "/coupling_times.json";
    fluidCsv_.open(outDir + "/fluid.csv");
    fluidCsv_
        << "time,water_volume,water_volume_outside_units\n"
        << std::setprecision(12);
}


void armourFoam::recording::resume
(
    const std::string& outDir,
    const bodyExchange& bodies,
    long records,
    double t
)
{
    std::vector<armour::RecorderUnit> units;
    for (const armour::UnitTemplate& u : bodies.units())
    {
        units.push_back({u.name, u.mesh});
    }
    bodies_ = armour::BodyRecorder::reopen
    (
        outDir + "/bodies.h5",
        outDir + "/bodies.xdmf",
        units,
        bodies.bodyUnit(),
        records
    );
    timesFile_ = outDir + "/coupling_times.json";
    keepRowsUpTo(outDir + "/fluid.csv", t);
    fluidCsv_.open(outDir + "/fluid.csv", std::ios::app);
    fluidCsv_ << std::setprecision(12);
}


void armourFoam::recording::openCsv(const std::string& path, double resumedAt)
{
    if (resumedAt >= 0)
    {
        keepRowsUpTo(path, resumedAt);
        csv_.open(path, std::ios::app);
        csv_ << std::setprecision(10);
        return;
    }
    csv_.open(path);
    if (!csv_)
    {
        FatalErrorInFunction
            << "cannot write " << path << Foam::exit(Foam::FatalError);
    }
    csv_
        << "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,"
           "Fx,Fy,Fz,Mx,My,Mz,Sx,Sy,Sz,chiVolume,engineTime\n";
    csv_ << std::setprecision(10);
}


bool armourFoam::recording::due(const Foam::Time& runTime)
{
    const double t = runTime.value();
    const double dtF = runTime.deltaTValue();
    const bool now =
        interval_ > 0
     && (
            t >= nextRecord_ - 1e-6*dtF
         || t + 0.5*dtF >= runTime.endTime().value()
        );
    if (now)
    {
        while (nextRecord_ <= t + 1e-6*dtF)
        {
            nextRecord_ += interval_;
        }
    }
    return now;
}


armourFoam::waterVolumes armourFoam::recording::water
(
    const Foam::fvMesh& mesh,
    const Foam::volScalarField& chi
)
{
    using namespace Foam;
    waterVolumes w;
    if (mesh.foundObject<volScalarField>("alpha.water"))
    {
        const volScalarField& alpha =
            mesh.lookupObject<volScalarField>("alpha.water");
        forAll(alpha, i)
        {
            w.all += alpha[i]*mesh.V()[i];
            w.outsideUnits += alpha[i]*(1 - chi[i])*mesh.V()[i];
        }
    }
    reduce(w.all, sumOp<scalar>());
    reduce(w.outsideUnits, sumOp<scalar>());
    return w;
}


void armourFoam::recording::record
(
    double t,
    const bodyExchange& bodies,
    const stepLoads& loads,
    const waterVolumes& water,
    const couplingTimes& times
)
{
    if (!bodies_)
    {
        return;
    }
    const armour::RigidBodyEngine& engine = bodies.engine();
    std::vector<armour::BodyState> states;
    for (int k = 0; k < engine.body_count(); ++k)
    {
        states.push_back(engine.state(k));
        states.back().external_force = loads.loads.force[k];
        states.back().external_torque = loads.loads.torque[k];
    }
    bodies_->append(t, states);
    fluidCsv_ << t << ',' << water.all << ',' << water.outsideUnits << std::endl;

    std::ofstream json(timesFile_);
    json
        << std::setprecision(9)
        << "{\"frozen\": " << (times.frozen ? "true" : "false")
        << ", \"coupling_steps\": " << times.steps
        << ", \"load_seconds\": " << times.loadSeconds
        << ", \"dem_seconds\": " << times.demSeconds
        << ", \"mask_seconds\": " << times.maskSeconds
        << ", \"replicas_identical\": "
        << (bodies.replicasIdentical() ? "true" : "false")
        << ", \"replica_position_spread\": " << bodies.replicaSpread()
        // Both clocks start at 0 (the cases' startTime); the engine keeps
        // the fluid's to half an engine step (frozen runs never advance).
        << std::setprecision(17)
        << ", \"fluid_time\": " << t
        << ", \"engine_time\": " << engine.time()
        << ", \"engine_time_step\": " << engine.time_step()
        << "}\n";
}


void armourFoam::recording::csvRow
(
    double t,
    const bodyExchange& bodies,
    const stepLoads& loads
)
{
    if (!csv_.is_open())
    {
        return;
    }
    const armour::RigidBodyEngine& engine = bodies.engine();
    for (int k = 0; k < engine.body_count(); ++k)
    {
        const armour::BodyState s = engine.state(k);
        const Eigen::Quaterniond& q = s.pose.orientation;
        const Eigen::Vector3d& F = loads.loads.force[k];
        const Eigen::Vector3d& M = loads.loads.torque[k];
        const Eigen::Vector3d& S = loads.source[k];
        csv_<< t << ',' << bodies.names()[k] << ','
            << s.pose.position.x() << ',' << s.pose.position.y() << ','
            << s.pose.position.z() << ','
            << q.w() << ',' << q.x() << ',' << q.y() << ',' << q.z() << ','
            << s.velocity.x() << ',' << s.velocity.y() << ','
            << s.velocity.z() << ','
            << s.angular_velocity.x() << ',' << s.angular_velocity.y()
            << ',' << s.angular_velocity.z() << ','
            << F.x() << ',' << F.y() << ',' << F.z() << ','
            << M.x() << ',' << M.y() << ',' << M.z() << ','
            << S.x() << ',' << S.y() << ',' << S.z() << ','
            << loads.chiVolume[k] << ',' << engine.time() << '\n';
    }
    csv_.flush();
}


// ************************************************************************* //
