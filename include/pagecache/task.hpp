#pragma once
// Task<T>: the lazy coroutine every simulated process is written in.
//
// A Task does nothing until it is awaited (or handed to Simulator::spawn). `co_await task`
// runs it and yields its value; an exception thrown inside is stored and rethrown at the
// co_await. Tasks are move-only and must be consumed ([[nodiscard]]).
//
// Resumption uses symmetric transfer: a task that completes after having suspended transfers
// control straight back to its awaiter. A task that completes without ever suspending (the
// common case of a "ready" sub-task) returns to its awaiter without resuming it recursively,
// so a loop awaiting 10^5 ready tasks keeps a flat stack even where the compiler does not
// turn symmetric transfer into a tail call (GCC at -O0, sanitizer builds).

#include <coroutine>
#include <cstddef>
#include <exception>
#include <type_traits>
#include <utility>
#include <variant>

namespace pagecache {

template <class T = void>
class Task;

namespace detail {

/// Coroutine frame memory (src/engine/frame_pool.cpp): recycled per size, per thread.
void* allocate_frame(std::size_t size);
void free_frame(void* frame, std::size_t size) noexcept;

class TaskPromiseBase {
 public:
  static void* operator new(std::size_t size) { return allocate_frame(size); }
  static void operator delete(void* frame, std::size_t size) noexcept { free_frame(frame, size); }

  // Where the task stands relative to the co_await that started it. While the awaiter's
  // await_suspend is still on the stack, a completing task must return to it (Inline ->
  // CompletedInline) instead of resuming the awaiter a second time.
  enum class Start { NotStarted, Inline, CompletedInline, Detached };

  std::suspend_always initial_suspend() const noexcept { return {}; }

  struct FinalAwaiter {
    bool await_ready() const noexcept { return false; }
    template <class Promise>
    std::coroutine_handle<> await_suspend(std::coroutine_handle<Promise> self) noexcept {
      TaskPromiseBase& promise = self.promise();
      if (promise.start_ == Start::Inline) {
        promise.start_ = Start::CompletedInline;
        return std::noop_coroutine();
      }
      return promise.continuation_ ? promise.continuation_ : std::noop_coroutine();
    }
    void await_resume() const noexcept {}
  };
  FinalAwaiter final_suspend() const noexcept { return {}; }

  void set_continuation(std::coroutine_handle<> continuation) noexcept {
    continuation_ = continuation;
  }
  Start start() const noexcept { return start_; }
  void set_start(Start start) noexcept { start_ = start; }

 private:
  std::coroutine_handle<> continuation_;
  Start start_ = Start::NotStarted;
};

template <class T>
class TaskPromise final : public TaskPromiseBase {
 public:
  Task<T> get_return_object() noexcept;
  void unhandled_exception() noexcept { result_.template emplace<2>(std::current_exception()); }
  template <class U>
    requires std::is_convertible_v<U&&, T>
  void return_value(U&& value) {
    result_.template emplace<1>(std::forward<U>(value));
  }
  T take_result() {
    if (result_.index() == 2) std::rethrow_exception(std::get<2>(result_));
    return std::move(std::get<1>(result_));
  }

 private:
  std::variant<std::monostate, T, std::exception_ptr> result_;
};

template <>
class TaskPromise<void> final : public TaskPromiseBase {
 public:
  Task<void> get_return_object() noexcept;
  void unhandled_exception() noexcept { exception_ = std::current_exception(); }
  void return_void() noexcept {}
  void take_result() {
    if (exception_) std::rethrow_exception(exception_);
  }

 private:
  std::exception_ptr exception_;
};

}  // namespace detail

template <class T>
class [[nodiscard]] Task {
 public:
  using promise_type = detail::TaskPromise<T>;
  using Handle = std::coroutine_handle<promise_type>;

  Task() noexcept = default;
  explicit Task(Handle handle) noexcept : handle_(handle) {}
  Task(Task&& other) noexcept : handle_(std::exchange(other.handle_, {})) {}
  Task& operator=(Task&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, {});
    }
    return *this;
  }
  Task(const Task&) = delete;
  Task& operator=(const Task&) = delete;
  ~Task() { reset(); }

  /// True if this Task holds a coroutine (false after a move).
  bool valid() const noexcept { return static_cast<bool>(handle_); }

  // A Task is its own awaiter: an awaiter object beside it would take a slot of its own in the
  // awaiting coroutine's frame, one per co_await (GCC does not share frame slots).
  bool await_ready() const noexcept { return !handle_ || handle_.done(); }
  bool await_suspend(std::coroutine_handle<> awaiting) noexcept {
    auto& promise = handle_.promise();
    promise.set_continuation(awaiting);
    promise.set_start(detail::TaskPromiseBase::Start::Inline);
    handle_.resume();
    if (promise.start() == detail::TaskPromiseBase::Start::CompletedInline) return false;
    promise.set_start(detail::TaskPromiseBase::Start::Detached);
    return true;
  }
  T await_resume() { return handle_.promise().take_result(); }

 private:
  void reset() noexcept {
    if (handle_) handle_.destroy();
    handle_ = {};
  }
  Handle handle_;
};

namespace detail {
template <class T>
Task<T> TaskPromise<T>::get_return_object() noexcept {
  return Task<T>(std::coroutine_handle<TaskPromise<T>>::from_promise(*this));
}
inline Task<void> TaskPromise<void>::get_return_object() noexcept {
  return Task<void>(std::coroutine_handle<TaskPromise<void>>::from_promise(*this));
}
}  // namespace detail

}  // namespace pagecache
