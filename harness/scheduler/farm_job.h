// A frame range on a farm (docs/FARM.md): the job folder `obscura farm submit` writes beside the
// output, which the scheduler's tasks, `farm status` and `farm resubmit` read. The folder holds
// job.json (what to render and every submission to the scheduler), task.sh (one array task: a chunk
// of frames through the ordinary `obscura render`), tasks/<i>.state (what each task last did) and
// logs/ (each task's output).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace obscura::harness::farm {

struct TaskState {
    std::string state = "pending";  // pending (never started), running, done, failed
    int exitCode = 0;               // of the task's last `obscura render`
    int attempts = 0;               // starts of the task, over every submission and requeue
};

struct Submission {
    std::string jobId;              // the scheduler's array job id
    std::vector<int> tasks;         // array indices it runs
};

struct FarmJob {
    std::filesystem::path folder;   // the job folder (absolute)
    std::string obscura;            // the harness the tasks run (absolute; shared file system)
    std::string scene;              // absolute
    std::string output;             // absolute pattern with ####
    long long firstFrame = 1;
    long long lastFrame = 1;
    long long chunk = 1;            // frames per task
    std::string partition;          // empty: the scheduler's default
    std::vector<std::string> renderArgs;
    int maxRetries = 2;             // restarts of a task (device failures inside it, requeues) before it gives up
    bool force = false;             // the first submission renders frames that exist already
    std::vector<Submission> submissions;

    int taskCount() const { return int((lastFrame - firstFrame) / chunk + 1); }
    long long taskFirstFrame(int task) const { return firstFrame + task * chunk; }
    long long taskLastFrame(int task) const { return std::min(lastFrame, taskFirstFrame(task) + chunk - 1); }
    std::string framePathOf(long long frame) const;
    std::filesystem::path taskScript() const { return folder / "task.sh"; }
    std::filesystem::path logFolder() const { return folder / "logs"; }
    std::filesystem::path stateFile(int task) const { return folder / "tasks" / (std::to_string(task) + ".state"); }
    TaskState taskState(int task) const;
};

// The job folder for an output pattern: <output folder>/.obscura-farm/<output name without #### and extension>.
std::filesystem::path jobFolderFor(const std::string& outputPattern);

// job.json and task.sh into job.folder (created); returns "" or the problem.
std::string save(const FarmJob& job);
// job.json of a job folder (or the file itself).
std::optional<FarmJob> load(const std::filesystem::path& folderOrFile, std::string& problem);

// Remembers which folder a scheduler job id belongs to ($XDG_STATE_HOME/obscura/farm-jobs, else
// ~/.local/state/obscura/farm-jobs), so `farm status JOB` takes the id `farm submit` printed.
void remember(const std::string& jobId, const std::filesystem::path& folder);
// A job id remembered, or a job folder / job.json path.
std::optional<FarmJob> find(const std::string& jobOrFolder, std::string& problem);

}  // namespace obscura::harness::farm
