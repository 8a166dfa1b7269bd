// The scheduler, through its ordinary command-line tools (sbatch, squeue, sacct): Slurm here; the
// same three calls map onto OpenCue, Deadline or Tractor (docs/FARM.md).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace obscura::harness::farm {

struct CommandResult {
    int exitCode = -1;      // -1: could not be started
    std::string output;     // stdout and stderr together
};

// Runs argv[0] (searched on PATH) with the arguments, no shell in between.
CommandResult runCommand(const std::vector<std::string>& argv);

struct ArraySubmit {
    std::string script;             // the task script
    std::vector<int> tasks;         // array indices
    std::string jobName;
    std::string partition;          // empty: the default
    std::string logPattern;         // --output, with %A (job) and %a (task)
    std::string workingFolder;
    std::vector<std::string> environment;  // NAME=value exported to the tasks beside the submitter's own
};

// sbatch --parsable --array=...: the job id, or "" with `problem` set.
std::string submitArray(const ArraySubmit& submit, std::string& problem);

// The scheduler's state of each array task of a job (PENDING, RUNNING, COMPLETED, FAILED, CANCELLED,
// TIMEOUT, NODE_FAIL, OUT_OF_MEMORY...): squeue for what it still knows, sacct for the rest where
// accounting is on. Tasks the scheduler no longer knows are absent.
std::map<int, std::string> taskStates(const std::string& jobId);

// "1,3,5-7" for sbatch --array.
std::string arraySpec(const std::vector<int>& tasks);

}  // namespace obscura::harness::farm
