#include "gpu/pipeline_cache.h"

#include "gpu/context.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <set>
#include <thread>

namespace obscura::gpu {

void PipelineCache::prepare(const std::vector<const Request*>& requests) {
    std::vector<const Request*> missing;
    std::set<std::string> named;
    for (const Request* r : requests)
        if (!pipelines_.contains(r->key) && named.insert(r->key).second) missing.push_back(r);
    if (missing.empty()) return;

    std::vector<std::unique_ptr<Pipeline>> built(missing.size());
    std::vector<std::exception_ptr> failures(missing.size());
    std::atomic<size_t> next{0};
    auto buildSome = [&] {
        for (size_t i; (i = next.fetch_add(1)) < missing.size();) {
            try {
                built[i] = missing[i]->build(device_);
            } catch (...) {
                failures[i] = std::current_exception();
            }
        }
    };
    {
        Context::HeldLog held(device_.context());
        const size_t threads = std::min<size_t>(missing.size(), std::max(1u, std::thread::hardware_concurrency()));
        std::vector<std::jthread> helpers;
        for (size_t t = 1; t < threads; ++t) helpers.emplace_back(buildSome);
        buildSome();
    }  // the helpers joined, then the held messages logged
    for (size_t i = 0; i < missing.size(); ++i)
        if (built[i]) pipelines_.emplace(missing[i]->key, std::move(built[i]));
    for (const std::exception_ptr& failure : failures)
        if (failure) std::rethrow_exception(failure);
}

const Pipeline& PipelineCache::get(const Request& request) {
    auto it = pipelines_.find(request.key);
    if (it != pipelines_.end()) return *it->second;
    return *pipelines_.emplace(request.key, request.build(device_)).first->second;
}

}  // namespace obscura::gpu
