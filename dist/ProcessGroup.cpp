/// \file ProcessGroup.cpp
/// The leader and its followers (ProcessGroup.h): a small command protocol broadcast from rank 0
/// on a communicator of its own, so it can never match a message of the solver's.

#include "dist/ProcessGroup.h"

#include <petscsys.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>

#include "dist/DistributedPoisson.h"
#include "dist/PetscReference.h"

namespace gale::dist {

namespace {

enum Command : int { STOP = 0, SYSTEM = 1, SOLVE = 2, RELEASE = 3, GAMG = 4 };

/// The running group (one per process) and its command channel.
ProcessGroup* gGroup = nullptr;
GroupSolveStats gLastStats;
MPI_Comm gChannel = MPI_COMM_NULL;

bool launchedByMpi() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(name)) return true;
    return false;
}

void broadcast(void* data, int count, MPI_Datatype type) {
    if (count > 0) MPI_Bcast(data, count, type, 0, gChannel);
}

void sendCommand(int command, int argument = 0) {
    int message[2] = {command, argument};
    broadcast(message, 2, MPI_INT);
}

/// The system, leader to followers (the leader's own copy is `system`).
void broadcastSystem(sim::PoissonSystem& system) {
    int header[10] = {system.nx, system.ny, system.nz, system.zLineSmoothing ? 1 : 0};
    for (int s = 0; s < 6; ++s)
        header[4 + s] = system.sides[size_t(s)] == sim::BoundaryKind::Neumann ? 1 : 0;
    broadcast(header, 10, MPI_INT);
    system.nx = header[0], system.ny = header[1], system.nz = header[2];
    system.zLineSmoothing = header[3] != 0;
    for (int s = 0; s < 6; ++s)
        system.sides[size_t(s)] =
            header[4 + s] ? sim::BoundaryKind::Neumann : sim::BoundaryKind::Dirichlet;
    system.weightX.resize(system.count(sim::Placement::FaceX));
    system.weightY.resize(system.count(sim::Placement::FaceY));
    system.weightZ.resize(system.count(sim::Placement::FaceZ));
    for (auto* w : {&system.weightX, &system.weightY, &system.weightZ})
        broadcast(w->data(), int(w->size()), MPI_FLOAT);
}

/// One solve's inputs, leader to followers.
void broadcastSolve(std::vector<double>& rhs, std::vector<double>& warm,
                    sim::SolverSettings& settings) {
    double tol = settings.relativeTolerance;
    long long sizes[2] = {(long long)rhs.size(), (long long)warm.size()};
    int ints[3] = {settings.maxIterations, settings.smoothingSweeps, settings.useMultigrid ? 1 : 0};
    broadcast(&tol, 1, MPI_DOUBLE);
    broadcast(sizes, 2, MPI_LONG_LONG);
    broadcast(ints, 3, MPI_INT);
    settings.relativeTolerance = tol;
    settings.maxIterations = ints[0], settings.smoothingSweeps = ints[1];
    settings.useMultigrid = ints[2] != 0;
    rhs.resize(size_t(sizes[0]));
    warm.resize(size_t(sizes[1]));
    broadcast(rhs.data(), int(rhs.size()), MPI_DOUBLE);
    broadcast(warm.data(), int(warm.size()), MPI_DOUBLE);
}

[[noreturn]] void abortGroup(int rank, const char* what) {
    std::fprintf(stderr, "gale: error: rank %d: %s\n", rank, what);
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 2);
    std::abort();
}

}  // namespace

ProcessGroup::ProcessGroup() {
    if (!launchedByMpi()) return;
    // gale's own handlers remove its temporaries on SIGINT/SIGTERM; PETSc's would not.
    if (PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr) != 0 ||
        PetscInitializeNoArguments() != 0)
        throw std::runtime_error("PETSc: PetscInitialize failed");
    mPetsc = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &mRank);
    MPI_Comm_size(MPI_COMM_WORLD, &mSize);
    MPI_Comm_dup(MPI_COMM_WORLD, &gChannel);
    gGroup = this;
}

ProcessGroup::~ProcessGroup() {
    if (!mPetsc) return;
    if (leader() && !mFinished) finish(0);
    gGroup = nullptr;
    MPI_Comm_free(&gChannel);
    PetscFinalize();
}

void ProcessGroup::finish(int exitCode) {
    if (!leader() || mFinished || !mPetsc) return;
    mFinished = true;
    if (mSize > 1) sendCommand(STOP, exitCode);
}

int ProcessGroup::serve() {
    std::unique_ptr<DistributedPoissonSolver> solver;
    for (;;) {
        int message[2] = {STOP, 0};
        broadcast(message, 2, MPI_INT);
        try {
            switch (message[0]) {
                case STOP:
                    return message[1];
                case SYSTEM: {
                    sim::PoissonSystem system;
                    broadcastSystem(system);
                    solver.reset();
                    solver = std::make_unique<DistributedPoissonSolver>(system, MPI_COMM_WORLD);
                    break;
                }
                case SOLVE: {
                    std::vector<double> rhs, warm;
                    sim::SolverSettings settings;
                    broadcastSolve(rhs, warm, settings);
                    if (!solver) abortGroup(mRank, "a solve without a system");
                    (void)solver->solve(rhs, warm, settings);
                    break;
                }
                case RELEASE:
                    solver.reset();
                    break;
                case GAMG: {
                    sim::PoissonSystem system;
                    broadcastSystem(system);
                    std::vector<double> rhs, unused;
                    sim::SolverSettings settings;
                    broadcastSolve(rhs, unused, settings);
                    (void)solveWithGamg(system, rhs, settings.relativeTolerance, MPI_COMM_WORLD);
                    break;
                }
                default:
                    abortGroup(mRank, "unknown command from rank 0");
            }
        } catch (const std::invalid_argument&) {
            // A setting checked before any communication: the leader meets the same error and
            // reports it; wait for its next command.
        } catch (const std::logic_error&) {
        } catch (const std::bad_alloc&) {
            abortGroup(mRank, "out of memory");
        } catch (const std::exception& e) {
            abortGroup(mRank, e.what());
        }
    }
}

GroupSolveStats lastGroupSolveStats() { return gLastStats; }

PoissonSolveFunction groupPoissonSolve(const sim::PoissonSystem& system) {
    if (!gGroup || gGroup->size() < 2 || !gGroup->leader()) return {};
    sendCommand(SYSTEM);
    sim::PoissonSystem copy = system;
    broadcastSystem(copy);
    // Followers drop their solver when the leader's is destroyed, at the same point.
    struct Shared {
        std::unique_ptr<DistributedPoissonSolver> solver;
        ~Shared() {
            if (gGroup) sendCommand(RELEASE);
        }
    };
    auto shared = std::make_shared<Shared>();
    shared->solver = std::make_unique<DistributedPoissonSolver>(system, MPI_COMM_WORLD);
    return [shared](const std::vector<double>& rhs, std::vector<double>& solution,
                    const sim::SolverSettings& settings) {
        sendCommand(SOLVE);
        std::vector<double> b = rhs;
        sim::SolverSettings s = settings;
        broadcastSolve(b, solution, s);
        const sim::SolveReport rep = shared->solver->solve(rhs, solution, settings);
        gLastStats = {shared->solver->stats(), shared->solver->decomposition()};
        return rep;
    };
}

ReferenceSolve groupGamgSolve(const sim::PoissonSystem& system, const std::vector<double>& rhs,
                              double relativeTolerance) {
    if (!gGroup) throw std::runtime_error("PETSc GAMG: needs the process group of mpirun");
    if (gGroup->size() > 1 && gGroup->leader()) {
        sendCommand(GAMG);
        sim::PoissonSystem copy = system;
        broadcastSystem(copy);
        std::vector<double> b = rhs, unused;
        sim::SolverSettings settings;
        settings.relativeTolerance = relativeTolerance;
        broadcastSolve(b, unused, settings);
    }
    return solveWithGamg(system, rhs, relativeTolerance, MPI_COMM_WORLD);
}

}  // namespace gale::dist
