#include "harness/scheduler/farm_job.h"

#include "harness/frame_output.h"

#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace obscura::harness::farm {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// One word for bash, whatever it holds.
std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

fs::path registryFolder() {
    const char* state = std::getenv("XDG_STATE_HOME");
    const char* home = std::getenv("HOME");
    fs::path base = state && *state ? fs::path(state) : fs::path(home ? home : ".") / ".local" / "state";
    return base / "obscura" / "farm-jobs";
}

// One array task: the chunk's frames through the ordinary `obscura render`, which writes each frame
// under a temporary name and renames it when complete; frames already on disk are skipped (a re-run
// resumes). A device or plugin failure (exit 4) is retried in place; bad input (exit 3) is not: the
// scene will not fix itself. Every start counts against maxRetries, so a task that keeps dying (a
// node failure requeues it) gives up instead of running forever.
std::string taskScript(const FarmJob& job) {
    std::ostringstream s;
    std::string args;
    for (const auto& a : job.renderArgs) args += " " + shellQuote(a);
    s << "#!/usr/bin/env bash\n"
      << "# Written by `obscura farm submit`: array task $SLURM_ARRAY_TASK_ID renders its chunk of frames.\n"
      << "set -u\n"
      << "task=${SLURM_ARRAY_TASK_ID:?not an array task}\n"
      << "first=$(( " << job.firstFrame << " + task * " << job.chunk << " ))\n"
      << "last=$(( first + " << job.chunk - 1 << " )); [ \"$last\" -gt " << job.lastFrame << " ] && last="
      << job.lastFrame << "\n"
      << "state=" << shellQuote((job.folder / "tasks").string()) << "/$task.state\n"
      << "attempt=$(( $(cut -d' ' -f3 \"$state\" 2>/dev/null || echo 0) + 1 ))\n"
      << "echo \"obscura farm: task ${SLURM_ARRAY_JOB_ID:-?}_$task on $(hostname): frames $first-$last, attempt "
         "$attempt\"\n"
      << "if [ \"$attempt\" -gt " << job.maxRetries + 1 << " ]; then\n"
      << "  echo \"obscura farm: task $task gave up after " << job.maxRetries + 1 << " attempts\" >&2\n"
      << "  echo \"failed 3 $attempt\" >\"$state\"; exit 3\n"
      << "fi\n"
      << "echo \"running 0 $attempt\" >\"$state\"\n"
      << "skip=" << (job.force ? "" : "--skip-existing") << "\n"
      << "[ -n \"${OBSCURA_FARM_RESUBMITTED:-}\" ] && skip=--skip-existing\n"
      << "retries=0\n"
      << "while :; do\n"
      << "  " << shellQuote(job.obscura) << " render " << shellQuote(job.scene) << " -o " << shellQuote(job.output)
      << " --frames \"$first-$last\" $skip" << args << "\n"
      << "  rc=$?\n"
      << "  if [ \"$rc\" -eq 4 ] && [ \"$retries\" -lt " << job.maxRetries << " ]; then\n"
      << "    retries=$(( retries + 1 )); echo \"obscura farm: device or plugin failure, retry $retries\" >&2; continue\n"
      << "  fi\n"
      << "  break\n"
      << "done\n"
      << "if [ \"$rc\" -eq 0 ]; then echo \"done 0 $attempt\" >\"$state\"; else echo \"failed $rc $attempt\" >\"$state\"; "
         "fi\n"
      << "echo \"obscura farm: task $task exit $rc\"\n"
      << "exit \"$rc\"\n";
    return s.str();
}

}  // namespace

std::string FarmJob::framePathOf(long long frame) const { return framePath(output, double(frame)); }

TaskState FarmJob::taskState(int task) const {
    TaskState t;
    std::ifstream in(stateFile(task));
    if (in) in >> t.state >> t.exitCode >> t.attempts;
    return t;
}

fs::path jobFolderFor(const std::string& outputPattern) {
    fs::path out = fs::absolute(outputPattern);
    std::string name = out.stem().string();
    std::string clean;
    for (char c : name)
        if (c != '#') clean += c;
    while (!clean.empty() && (clean.back() == '.' || clean.back() == '_' || clean.back() == '-')) clean.pop_back();
    return out.parent_path() / ".obscura-farm" / (clean.empty() ? "frames" : clean);
}

std::string save(const FarmJob& job) {
    std::error_code ec;
    fs::create_directories(job.folder / "tasks", ec);
    fs::create_directories(job.logFolder(), ec);
    if (ec) return job.folder.string() + ": " + ec.message();
    json submissions = json::array();
    for (const auto& s : job.submissions) submissions.push_back({{"jobId", s.jobId}, {"tasks", s.tasks}});
    json doc = {{"obscura", job.obscura},         {"scene", job.scene},         {"output", job.output},
                {"firstFrame", job.firstFrame},   {"lastFrame", job.lastFrame}, {"chunk", job.chunk},
                {"partition", job.partition},     {"renderArgs", job.renderArgs}, {"maxRetries", job.maxRetries},
                {"force", job.force},             {"submissions", submissions}};
    std::ofstream(job.folder / "job.json") << doc.dump(2) << "\n";
    std::ofstream script(job.taskScript());
    script << taskScript(job);
    script.close();
    fs::permissions(job.taskScript(), fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                          fs::perms::others_read | fs::perms::others_exec, ec);
    return script ? "" : job.taskScript().string() + ": cannot be written";
}

std::optional<FarmJob> load(const fs::path& folderOrFile, std::string& problem) {
    fs::path file = fs::is_directory(folderOrFile) ? folderOrFile / "job.json" : folderOrFile;
    std::ifstream in(file);
    if (!in) {
        problem = file.string() + ": no farm job there";
        return std::nullopt;
    }
    try {
        json doc = json::parse(in);
        FarmJob job;
        job.folder = fs::absolute(file).parent_path();
        job.obscura = doc.at("obscura");
        job.scene = doc.at("scene");
        job.output = doc.at("output");
        job.firstFrame = doc.at("firstFrame");
        job.lastFrame = doc.at("lastFrame");
        job.chunk = doc.at("chunk");
        job.partition = doc.value("partition", "");
        job.renderArgs = doc.value("renderArgs", std::vector<std::string>{});
        job.maxRetries = doc.value("maxRetries", 2);
        job.force = doc.value("force", false);
        for (const auto& s : doc.at("submissions"))
            job.submissions.push_back({s.at("jobId"), s.at("tasks").get<std::vector<int>>()});
        if (job.chunk < 1 || job.lastFrame < job.firstFrame) throw std::runtime_error("bad frame range");
        return job;
    } catch (const std::exception& e) {
        problem = file.string() + ": " + e.what();
        return std::nullopt;
    }
}

void remember(const std::string& jobId, const fs::path& folder) {
    std::error_code ec;
    fs::create_directories(registryFolder(), ec);
    std::ofstream(registryFolder() / jobId) << folder.string() << "\n";
}

std::optional<FarmJob> find(const std::string& jobOrFolder, std::string& problem) {
    std::error_code ec;
    if (fs::exists(jobOrFolder, ec)) return load(jobOrFolder, problem);
    std::ifstream in(registryFolder() / jobOrFolder);
    std::string folder;
    if (!in || !std::getline(in, folder)) {
        problem = "no farm job '" + jobOrFolder + "' (give the id `obscura farm submit` printed, or the job folder)";
        return std::nullopt;
    }
    return load(folder, problem);
}

}  // namespace obscura::harness::farm
