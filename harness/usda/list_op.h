// A list-edit opinion (SdfListOp): either an explicit list, or edits applied to weaker opinions.
#pragma once

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

namespace obscura::usda {

enum class ListOpKind { Explicit, Prepend, Append, Add, Delete, Reorder };

template <class T>
struct ListOp {
    std::optional<std::vector<T>> explicitItems;
    std::vector<T> prepended, appended, added, deleted, ordered;

    bool hasOpinion() const {
        return explicitItems || !prepended.empty() || !appended.empty() || !added.empty() || !deleted.empty() ||
               !ordered.empty();
    }

    // As in a layer: an explicit list replaces all edits; an edit ends the explicit mode.
    void set(ListOpKind kind, std::vector<T> items) {
        if (kind == ListOpKind::Explicit) {
            *this = ListOp{};
            explicitItems = std::move(items);
            return;
        }
        explicitItems.reset();
        switch (kind) {
        case ListOpKind::Prepend: prepended = std::move(items); break;
        case ListOpKind::Append: appended = std::move(items); break;
        case ListOpKind::Add: added = std::move(items); break;
        case ListOpKind::Delete: deleted = std::move(items); break;
        case ListOpKind::Reorder: ordered = std::move(items); break;
        case ListOpKind::Explicit: break;
        }
    }

    // This opinion applied over the weaker result, in Sdf's order: delete, add, prepend, append,
    // reorder (reordered items move to the front in the given order).
    std::vector<T> applyTo(std::vector<T> result) const {
        if (explicitItems) return *explicitItems;
        auto contains = [](const std::vector<T>& v, const T& x) { return std::find(v.begin(), v.end(), x) != v.end(); };
        auto removeAll = [&](const std::vector<T>& items) {
            std::erase_if(result, [&](const T& x) { return contains(items, x); });
        };
        removeAll(deleted);
        for (const T& x : added)
            if (!contains(result, x)) result.push_back(x);
        removeAll(prepended);
        result.insert(result.begin(), prepended.begin(), prepended.end());
        removeAll(appended);
        result.insert(result.end(), appended.begin(), appended.end());
        if (!ordered.empty()) {
            std::vector<T> front;
            for (const T& x : ordered)
                if (contains(result, x) && !contains(front, x)) front.push_back(x);
            removeAll(front);
            result.insert(result.begin(), front.begin(), front.end());
        }
        return result;
    }

    // The same edits with every item converted (paths remapped, asset paths resolved).
    template <class F>
    auto transformed(F f) const {
        using U = decltype(f(std::declval<const T&>()));
        auto convert = [&](const std::vector<T>& items) {
            std::vector<U> out;
            out.reserve(items.size());
            for (const T& x : items) out.push_back(f(x));
            return out;
        };
        ListOp<U> out;
        if (explicitItems) out.explicitItems = convert(*explicitItems);
        out.prepended = convert(prepended);
        out.appended = convert(appended);
        out.added = convert(added);
        out.deleted = convert(deleted);
        out.ordered = convert(ordered);
        return out;
    }
};

// Composes opinions given strongest first into the resulting list.
template <class T>
std::vector<T> composeListOps(const std::vector<const ListOp<T>*>& strongestFirst) {
    std::vector<T> result;
    for (auto it = strongestFirst.rbegin(); it != strongestFirst.rend(); ++it) result = (*it)->applyTo(std::move(result));
    return result;
}

}  // namespace obscura::usda
