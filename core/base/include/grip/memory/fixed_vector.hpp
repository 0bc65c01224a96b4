#pragma once
// Vectors whose capacity is fixed before the first element goes in.
//
//   VectorView<T>        the capacity-free interface that functions take (ETL's `ivector<T>`), so
//                        code is not a template on every capacity.
//   FixedVector<T, N>    capacity in the type, storage inline: no heap at all.
//   BoundedVector<T>     capacity chosen at start-up, one allocation in the constructor.
//
// After construction nothing allocates and nothing throws: a full vector refuses
// (`push_back` returns false, `emplace_back` returns nullptr) and never grows. Broken contracts
// (index out of range, `front()`/`pop_back()` on an empty vector) go to GRIP_ASSERT.
// Elements must be nothrow copy constructible and nothrow destructible; only live elements
// are constructed, so T need not be default constructible.

#include <cstddef>
#include <cstring>
#include <memory>
#include <new>
#include <span>
#include <type_traits>
#include <utility>

#include "grip/common/assert.hpp"

namespace grip {

template <typename T>
class VectorView {
  static_assert(std::is_nothrow_copy_constructible_v<T>,
                "VectorView<T>: T must be nothrow copyable");
  static_assert(std::is_nothrow_destructible_v<T>, "VectorView<T>: T must be nothrow destructible");

 public:
  using value_type = T;
  using size_type = std::size_t;
  using iterator = T*;
  using const_iterator = const T*;

  VectorView(const VectorView&) = delete;
  VectorView& operator=(const VectorView&) = delete;

  std::size_t size() const noexcept { return size_; }
  std::size_t capacity() const noexcept { return capacity_; }
  bool empty() const noexcept { return size_ == 0; }
  bool full() const noexcept { return size_ == capacity_; }

  T* data() noexcept { return data_; }
  const T* data() const noexcept { return data_; }

  // Panics when i >= size().
  T& operator[](std::size_t i) noexcept {
    GRIP_ASSERT(i < size_);
    return data_[i];
  }
  const T& operator[](std::size_t i) const noexcept {
    GRIP_ASSERT(i < size_);
    return data_[i];
  }

  T* begin() noexcept { return data_; }
  T* end() noexcept { return data_ + size_; }
  const T* begin() const noexcept { return data_; }
  const T* end() const noexcept { return data_ + size_; }

  // Panic when empty.
  T& front() noexcept { return (*this)[0]; }
  const T& front() const noexcept { return (*this)[0]; }
  T& back() noexcept {
    GRIP_ASSERT(size_ > 0);
    return data_[size_ - 1];
  }
  const T& back() const noexcept {
    GRIP_ASSERT(size_ > 0);
    return data_[size_ - 1];
  }

  // Appends a copy of `value`. Returns false, and changes nothing, when full.
  [[nodiscard]] bool push_back(const T& value) noexcept { return emplace_back(value) != nullptr; }

  // Constructs an element in place from `args` (with parentheses, or with braces for an
  // aggregate). Returns it, or nullptr (changing nothing) when full.
  template <typename... Args>
  [[nodiscard]] T* emplace_back(Args&&... args) noexcept {
    if (full()) {
      return nullptr;
    }
    void* slot = static_cast<void*>(data_ + size_);
    T* element = nullptr;
    if constexpr (std::is_constructible_v<T, Args...>) {
      static_assert(std::is_nothrow_constructible_v<T, Args...>,
                    "emplace_back: T must be nothrow constructible from these arguments");
      element = ::new (slot) T(std::forward<Args>(args)...);
    } else {
      static_assert(noexcept(T{std::declval<Args>()...}),
                    "emplace_back: T must be nothrow constructible from these arguments");
      element = ::new (slot) T{std::forward<Args>(args)...};
    }
    ++size_;
    return element;
  }

  // Removes the last element. Panics when empty.
  void pop_back() noexcept {
    GRIP_ASSERT(size_ > 0);
    --size_;
    std::destroy_at(data_ + size_);
  }

  // Removes every element; capacity is unchanged.
  void clear() noexcept { truncate(0); }

  // Keeps the first n elements and destroys the rest. Panics when n > size().
  void truncate(std::size_t n) noexcept {
    GRIP_ASSERT(n <= size_);
    std::destroy(data_ + n, data_ + size_);
    size_ = n;
  }
  // Same as truncate(n): a vector of fixed capacity can only be resized down without a value.
  void resize_down(std::size_t n) noexcept { truncate(n); }

  std::span<T> span() noexcept { return {data_, size_}; }
  std::span<const T> span() const noexcept { return {data_, size_}; }

 protected:
  // `data` points at uninitialised storage for `capacity` elements, owned by the derived class.
  VectorView(T* data, std::size_t capacity) noexcept : data_(data), capacity_(capacity) {}
  ~VectorView() = default;

  // Storage of the derived class changes hands (moves).
  void rebind(T* data, std::size_t size, std::size_t capacity) noexcept {
    data_ = data;
    size_ = size;
    capacity_ = capacity;
  }

 private:
  T* data_;
  std::size_t size_ = 0;
  std::size_t capacity_;
};

// Capacity in the type, storage inline. Moving moves the elements one by one and leaves the
// source empty.
template <typename T, std::size_t N>
class FixedVector : public VectorView<T> {
  static_assert(N > 0, "FixedVector<T, N>: N must be positive");
  static_assert(std::is_nothrow_move_constructible_v<T>,
                "FixedVector<T, N>: T must be nothrow movable");

 public:
  FixedVector() noexcept : VectorView<T>(nullptr, 0) { this->rebind(slots(), 0, N); }
  ~FixedVector() { this->clear(); }

  FixedVector(const FixedVector&) = delete;
  FixedVector& operator=(const FixedVector&) = delete;

  FixedVector(FixedVector&& other) noexcept : VectorView<T>(nullptr, 0) {
    this->rebind(slots(), 0, N);
    take(other);
  }
  FixedVector& operator=(FixedVector&& other) noexcept {
    if (this != &other) {
      this->clear();
      take(other);
    }
    return *this;
  }

 private:
  T* slots() noexcept { return reinterpret_cast<T*>(storage_); }

  void take(FixedVector& other) noexcept {
    for (T& element : other) {
      static_cast<void>(this->emplace_back(std::move(element)));
    }
    other.clear();
  }

  alignas(T) std::byte storage_[N * sizeof(T)];
};

// Capacity chosen at construction; the only allocation happens there (it may throw
// std::bad_alloc: construct at start-up, not on the real-time path). Moving transfers the
// storage and leaves the source empty with capacity 0.
template <typename T>
class BoundedVector : public VectorView<T> {
 public:
  explicit BoundedVector(std::size_t capacity)
      : VectorView<T>(nullptr, 0), storage_(allocate(capacity)) {
    this->rebind(storage_.get(), 0, capacity);
  }
  ~BoundedVector() { this->clear(); }

  BoundedVector(const BoundedVector&) = delete;
  BoundedVector& operator=(const BoundedVector&) = delete;

  BoundedVector(BoundedVector&& other) noexcept : VectorView<T>(nullptr, 0) { take(other); }
  BoundedVector& operator=(BoundedVector&& other) noexcept {
    if (this != &other) {
      this->clear();
      take(other);
    }
    return *this;
  }

 private:
  struct Free {
    void operator()(T* p) const noexcept { ::operator delete (p, std::align_val_t{alignof(T)}); }
  };
  using Storage = std::unique_ptr<T, Free>;

  static Storage allocate(std::size_t capacity) {
    GRIP_ASSERT(capacity <= static_cast<std::size_t>(-1) / sizeof(T));
    void* raw = ::operator new (capacity * sizeof(T), std::align_val_t{alignof(T)});
    // Touch every page now, at start-up, so that the first push_back in a real-time loop does
    // not take a page fault.
    std::memset(raw, 0, capacity * sizeof(T));
    return Storage(static_cast<T*>(raw));
  }

  void take(BoundedVector& other) noexcept {
    storage_ = std::move(other.storage_);
    this->rebind(storage_.get(), other.size(), other.capacity());
    other.rebind(nullptr, 0, 0);  // the elements now belong to *this
  }

  Storage storage_;
};

}  // namespace grip
