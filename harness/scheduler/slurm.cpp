#include "harness/scheduler/slurm.h"

#include <sstream>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace obscura::harness::farm {

CommandResult runCommand(const std::vector<std::string>& argv) {
    CommandResult result;
    int pipeFds[2];
    if (argv.empty() || pipe(pipeFds) != 0) return result;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDERR_FILENO);
    posix_spawn_file_actions_addclose(&actions, pipeFds[0]);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(pipeFds[1]);
    if (spawned == 0) {
        char buffer[4096];
        ssize_t n;
        while ((n = read(pipeFds[0], buffer, sizeof buffer)) > 0) result.output.append(buffer, size_t(n));
    }
    close(pipeFds[0]);
    if (spawned != 0) {
        result.output = argv[0] + ": cannot be started (is it installed and on PATH?)";
        return result;
    }
    int status = 0;
    waitpid(pid, &status, 0);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return result;
}

std::string arraySpec(const std::vector<int>& tasks) {
    std::string spec;
    for (size_t i = 0; i < tasks.size();) {
        size_t j = i;
        while (j + 1 < tasks.size() && tasks[j + 1] == tasks[j] + 1) ++j;
        if (!spec.empty()) spec += ",";
        spec += std::to_string(tasks[i]) + (j > i ? "-" + std::to_string(tasks[j]) : "");
        i = j + 1;
    }
    return spec;
}

std::string submitArray(const ArraySubmit& s, std::string& problem) {
    std::string exports = "ALL";
    for (const auto& e : s.environment) exports += "," + e;
    // --requeue: a task lost with its node goes back to the queue (its restarts count as attempts).
    std::vector<std::string> argv = {"sbatch",  "--parsable", "--requeue", "--array=" + arraySpec(s.tasks),
                                     "--job-name=" + s.jobName, "--output=" + s.logPattern,
                                     "--chdir=" + s.workingFolder, "--export=" + exports};
    if (!s.partition.empty()) argv.push_back("--partition=" + s.partition);
    argv.push_back(s.script);
    CommandResult r = runCommand(argv);
    std::string id = r.output.substr(0, r.output.find_first_of(";\n"));
    if (r.exitCode != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
        problem = "sbatch failed: " + r.output;
        return "";
    }
    return id;
}

namespace {

// Lines "JOB_TASK|STATE" (sacct) or "TASK|STATE" (squeue %K) into states by task.
void parseStates(const std::string& text, const std::string& jobId, std::map<int, std::string>& states) {
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        auto bar = line.find('|');
        if (bar == std::string::npos) continue;
        std::string task = line.substr(0, bar), state = line.substr(bar + 1);
        state = state.substr(0, state.find_first_of(" |"));  // "CANCELLED by 0" -> CANCELLED
        if (task.rfind(jobId + "_", 0) == 0) task = task.substr(jobId.size() + 1);
        if (task.empty() || task.find_first_not_of("0123456789") != std::string::npos) continue;
        states.emplace(std::stoi(task), state);  // the first source wins: squeue before sacct
    }
}

}  // namespace

std::map<int, std::string> taskStates(const std::string& jobId) {
    std::map<int, std::string> states;
    CommandResult queue = runCommand({"squeue", "--array", "--states=all", "--noheader", "--jobs=" + jobId,
                                      "--format=%K|%T"});
    if (queue.exitCode == 0) parseStates(queue.output, jobId, states);
    CommandResult accounting = runCommand({"sacct", "--noheader", "--parsable2", "--allocations", "--jobs=" + jobId,
                                           "--format=JobID,State"});
    if (accounting.exitCode == 0) parseStates(accounting.output, jobId, states);
    return states;
}

}  // namespace obscura::harness::farm
