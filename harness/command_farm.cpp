// `obscura farm`: frame ranges as array jobs on an existing scheduler (docs/FARM.md). Every task is
// the ordinary `obscura render` of a chunk of frames; the output folder itself says which frames are
// done, so a killed or failed task is resumed by rendering what is missing.
#include "harness/commands.h"
#include "harness/exit_codes.h"
#include "harness/scheduler/farm_job.h"
#include "harness/scheduler/slurm.h"
#include "harness/plugin_loader.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

namespace obscura::harness {
namespace fs = std::filesystem;
using farm::FarmJob;

namespace {

std::vector<std::string> splitWords(const std::vector<std::string>& values) {
    std::vector<std::string> words;
    for (const auto& v : values) {
        std::istringstream in(v);
        for (std::string w; in >> w;) words.push_back(w);
    }
    return words;
}

bool parseRange(const std::string& text, long long& first, long long& last) {
    auto dash = text.find('-', 1);
    try {
        size_t used = 0;
        first = std::stoll(text, &used);
        if (dash == std::string::npos) return used == text.size() && (last = first, true);
        if (used != dash) return false;
        last = std::stoll(text.substr(dash + 1), &used);
        return used == text.size() - dash - 1 && last >= first;
    } catch (const std::exception&) {
        return false;
    }
}

enum class TaskClass { Done, Running, Pending, Failed };

struct TaskReport {
    TaskClass kind = TaskClass::Pending;
    int framesDone = 0;
    int frames = 0;
    std::string why;       // for failed tasks: the scheduler's state or the render's exit code
    std::string jobId;     // of the submission that last ran it
};

bool schedulerIsActive(const std::string& state) {
    return state == "PENDING" || state == "CONFIGURING" || state == "REQUEUED" || state == "REQUEUE_HOLD" ||
           state == "REQUEUE_FED" || state == "RESIZING" || state == "SUSPENDED";
}

// What each task of the job is: its frames on disk first, the scheduler's word for the rest.
std::vector<TaskReport> reportTasks(const FarmJob& job) {
    std::map<int, std::string> lastJob;  // task -> id of the newest submission that holds it
    for (const auto& s : job.submissions)
        for (int t : s.tasks) lastJob[t] = s.jobId;
    std::map<std::string, std::map<int, std::string>> states;  // job id -> task -> scheduler state
    std::vector<TaskReport> reports(size_t(job.taskCount()));
    for (int t = 0; t < job.taskCount(); ++t) {
        TaskReport& r = reports[size_t(t)];
        for (long long f = job.taskFirstFrame(t); f <= job.taskLastFrame(t); ++f, ++r.frames)
            if (fs::exists(job.framePathOf(f))) ++r.framesDone;
        if (r.framesDone == r.frames) {
            r.kind = TaskClass::Done;
            continue;
        }
        r.jobId = lastJob.count(t) ? lastJob[t] : "";
        if (!r.jobId.empty() && !states.count(r.jobId)) states[r.jobId] = farm::taskStates(r.jobId);
        std::string scheduler = r.jobId.empty() || !states[r.jobId].count(t) ? "" : states[r.jobId][t];
        farm::TaskState own = job.taskState(t);
        if (scheduler == "RUNNING" || scheduler == "COMPLETING") {
            r.kind = TaskClass::Running;
        } else if (schedulerIsActive(scheduler)) {
            r.kind = TaskClass::Pending;
        } else if (own.state == "failed") {
            r.kind = TaskClass::Failed;
            r.why = "obscura render exit " + std::to_string(own.exitCode) + " (attempt " + std::to_string(own.attempts) + ")";
        } else if (!scheduler.empty()) {
            r.kind = TaskClass::Failed;
            r.why = scheduler == "COMPLETED" ? "completed without all its frames" : scheduler;
        } else if (own.state == "running") {
            r.kind = TaskClass::Failed;
            r.why = "lost: it started, and the scheduler no longer knows it";
        } else {
            r.kind = TaskClass::Failed;
            r.why = "not known to the scheduler";
        }
    }
    return reports;
}

std::string logOf(const FarmJob& job, const std::string& jobId, int task) {
    return (job.logFolder() / (jobId + "_" + std::to_string(task) + ".log")).string();
}

std::string submit(FarmJob& job, const std::vector<int>& tasks, bool resubmission) {
    farm::ArraySubmit s;
    s.script = job.taskScript().string();
    s.tasks = tasks;
    s.jobName = "obscura:" + fs::path(job.scene).filename().string();
    s.partition = job.partition;
    s.logPattern = (job.logFolder() / "%A_%a.log").string();
    s.workingFolder = job.folder.string();
    if (resubmission) s.environment.push_back("OBSCURA_FARM_RESUBMITTED=1");
    std::string problem;
    std::string id = farm::submitArray(s, problem);
    if (id.empty()) {
        std::fprintf(stderr, "obscura: %s\n", problem.c_str());
        return "";
    }
    job.submissions.push_back({id, tasks});
    if (std::string saved = farm::save(job); !saved.empty()) std::fprintf(stderr, "obscura: %s\n", saved.c_str());
    farm::remember(id, job.folder);
    return id;
}

// The job `farm submit` printed (or its folder); says why when there is none.
std::optional<FarmJob> findJob(const std::string& jobOrFolder) {
    std::string problem;
    auto job = farm::find(jobOrFolder, problem);
    if (!job) std::fprintf(stderr, "obscura: %s\n", problem.c_str());
    return job;
}

}  // namespace

int runFarmSubmit(const FarmSubmitOptions& o) {
    FarmJob job;
    if (!parseRange(o.frames, job.firstFrame, job.lastFrame)) {
        std::fprintf(stderr, "obscura: --frames expects A-B with integers A <= B, got '%s'\n", o.frames.c_str());
        return kExitUsage;
    }
    if (o.output.find('#') == std::string::npos) {
        std::fprintf(stderr, "obscura: the output of a frame range needs #### for the frame number: %s\n", o.output.c_str());
        return kExitUsage;
    }
    std::error_code ec;
    if (!fs::is_regular_file(o.scene, ec)) {
        std::fprintf(stderr, "obscura: %s: no such scene file\n", o.scene.c_str());
        return kExitBadInput;
    }
    job.obscura = (executableDir() / "obscura").string();
    job.scene = fs::absolute(o.scene).lexically_normal().string();
    job.output = fs::absolute(o.output).lexically_normal().string();
    job.chunk = o.chunk;
    job.partition = o.partition;
    job.renderArgs = splitWords(o.renderArgs);
    job.maxRetries = o.maxRetries;
    job.force = o.force;
    job.folder = farm::jobFolderFor(job.output);
    fs::remove_all(job.folder / "tasks", ec);  // a new submission starts its attempts afresh
    fs::create_directories(fs::path(job.output).parent_path(), ec);
    if (std::string problem = farm::save(job); !problem.empty()) {
        std::fprintf(stderr, "obscura: %s\n", problem.c_str());
        return kExitBadInput;
    }
    std::vector<int> tasks;
    for (int t = 0; t < job.taskCount(); ++t) tasks.push_back(t);
    std::string id = submit(job, tasks, false);
    if (id.empty()) return kExitPluginOrDevice;
    std::fprintf(stderr, "obscura: frames %lld-%lld in %d tasks of %lld, job folder %s\n", job.firstFrame,
                 job.lastFrame, job.taskCount(), job.chunk, job.folder.c_str());
    std::printf("%s\n", id.c_str());
    return kExitOk;
}

int runFarmStatus(const FarmJobOptions& o) {
    auto job = findJob(o.job);
    if (!job) return kExitUsage;
    auto reports = reportTasks(*job);
    int frames = 0, done = 0, running = 0, pending = 0, failed = 0;
    for (const auto& r : reports) {
        frames += r.frames;
        done += r.framesDone;
        int missing = r.frames - r.framesDone;
        (r.kind == TaskClass::Running ? running : r.kind == TaskClass::Pending ? pending : failed) +=
            r.kind == TaskClass::Done ? 0 : missing;
    }
    constexpr int kBar = 40;
    int filled = frames ? done * kBar / frames : kBar;
    std::printf("%s: frames %lld-%lld -> %s\n", fs::path(job->scene).filename().c_str(), job->firstFrame,
                job->lastFrame, job->output.c_str());
    std::printf("[%s%s] %d/%d frames done, %d running, %d pending, %d failed\n", std::string(size_t(filled), '#').c_str(),
                std::string(size_t(kBar - filled), '-').c_str(), done, frames, running, pending, failed);
    for (int t = 0; t < int(reports.size()); ++t)
        if (reports[size_t(t)].kind == TaskClass::Failed)
            std::printf("failed: task %d (frames %lld-%lld): %s; log %s\n", t, job->taskFirstFrame(t),
                        job->taskLastFrame(t), reports[size_t(t)].why.c_str(),
                        logOf(*job, reports[size_t(t)].jobId, t).c_str());
    return done == frames ? kExitOk : kExitBelowThreshold;
}

int runFarmResubmit(const FarmJobOptions& o) {
    auto job = findJob(o.job);
    if (!job) return kExitUsage;
    auto reports = reportTasks(*job);
    std::vector<int> tasks;
    int gaveUp = 0;
    for (int t = 0; t < int(reports.size()); ++t) {
        if (reports[size_t(t)].kind != TaskClass::Failed) continue;
        if (job->taskState(t).attempts > job->maxRetries) {
            std::fprintf(stderr, "obscura: task %d not resubmitted: it ran %d times (--max-retries %d); %s\n", t,
                         job->taskState(t).attempts, job->maxRetries, reports[size_t(t)].why.c_str());
            ++gaveUp;
            continue;
        }
        tasks.push_back(t);
    }
    if (tasks.empty()) {
        std::fprintf(stderr, "obscura: nothing to resubmit\n");
        return gaveUp ? kExitBadInput : kExitOk;
    }
    std::string id = submit(*job, tasks, true);
    if (id.empty()) return kExitPluginOrDevice;
    std::fprintf(stderr, "obscura: resubmitted tasks %s\n", farm::arraySpec(tasks).c_str());
    std::printf("%s\n", id.c_str());
    return kExitOk;
}

}  // namespace obscura::harness
