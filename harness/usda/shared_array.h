// An array whose copies share one payload until one of them is changed (copy on write), as
// OpenUSD's VtArray is: a composed attribute holds the very values its layer read, so composing a
// spec into many prims (a referenced asset, an inherited class) costs a pointer per value, not
// the values again.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <memory>
#include <vector>

namespace obscura::usda {

template <class T>
class SharedArray {
public:
    SharedArray() = default;
    // Takes over a built vector (implicit, so that builders hand their vectors over as they are).
    SharedArray(std::vector<T> elements)  // NOLINT(google-explicit-constructor)
        : payload_(elements.empty() ? nullptr : std::make_shared<std::vector<T>>(std::move(elements))) {}
    SharedArray(std::initializer_list<T> elements) : SharedArray(std::vector<T>(elements)) {}

    // std::vector's read interface.
    size_t size() const { return payload_ ? payload_->size() : 0; }
    bool empty() const { return size() == 0; }
    const T& operator[](size_t i) const { return (*payload_)[i]; }
    const T& at(size_t i) const { return vector().at(i); }
    const T& front() const { return payload_->front(); }
    const T& back() const { return payload_->back(); }
    const T* data() const { return payload_ ? payload_->data() : nullptr; }
    auto begin() const { return vector().begin(); }
    auto end() const { return vector().end(); }
    // The elements as a vector, for code that takes one (copying it copies the elements).
    const std::vector<T>& vector() const { return payload_ ? *payload_ : empty_; }
    operator const std::vector<T>&() const { return vector(); }  // NOLINT(google-explicit-constructor)

    // The one way to change the elements: first detaches from the copies that share them, which
    // keep theirs. The reference is good until this array is next copied.
    std::vector<T>& edit() {
        if (!payload_) payload_ = std::make_shared<std::vector<T>>();
        else if (payload_.use_count() > 1) payload_ = std::make_shared<std::vector<T>>(*payload_);
        return *payload_;
    }

    // What the payload is, so that memory shared by many arrays can be counted once; null when
    // empty.
    const void* payload() const { return payload_.get(); }
    // The heap the payload holds (the vector's capacity and the shared block around it).
    size_t payloadBytes() const {
        return payload_ ? sizeof(std::vector<T>) + kControlBlockBytes + payload_->capacity() * sizeof(T) : 0;
    }

    friend bool operator==(const SharedArray& a, const SharedArray& b) {
        return a.payload_ == b.payload_ || a.vector() == b.vector();
    }

private:
    // make_shared's control block: two counts and a vtable pointer.
    static constexpr size_t kControlBlockBytes = 16;
    static inline const std::vector<T> empty_{};
    std::shared_ptr<std::vector<T>> payload_;
};

}  // namespace obscura::usda
