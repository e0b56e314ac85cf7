// FunctionRef<R(Args...)>: a reference to a callable for the length of a call, which neither copies
// nor allocates (std::function may do both). The broad phase's queries take their callbacks this
// way, so that a query inside the step (the continuous pass, sensors) allocates nothing. It refers
// to the callable it was made from: keep that alive while the reference is used, and do not keep a
// FunctionRef made from a temporary beyond the call it was passed to.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <type_traits>
#include <utility>

namespace collide {

template <typename Signature>
class FunctionRef;

template <typename R, typename... Args>
class FunctionRef<R(Args...)> {
 public:
  FunctionRef() noexcept = default;
  FunctionRef(std::nullptr_t) noexcept {}
  // Any callable with this signature. An empty one (a null function pointer, an empty
  // std::function) makes an empty reference, which converts to false.
  template <typename F>
  requires(!std::is_same_v<std::remove_cvref_t<F>, FunctionRef> && std::is_invocable_r_v<R, F&, Args...>)
      FunctionRef(F&& f)
  noexcept {  // NOLINT: implicit, as std::function's
    if constexpr (std::is_constructible_v<bool, F&> && !std::is_class_v<std::remove_cvref_t<F>>) {
      if (!static_cast<bool>(f)) return;  // a null function pointer
    } else if constexpr (
        requires { static_cast<bool>(f); } && requires { f.target_type(); }) {
      if (!static_cast<bool>(f)) return;  // an empty std::function
    }
    callable_ = const_cast<void*>(static_cast<const void*>(std::addressof(f)));
    call_ = [](void* callable, Args... args) -> R {
      return std::invoke(*static_cast<std::add_pointer_t<std::remove_reference_t<F>>>(callable),
                         std::forward<Args>(args)...);
    };
  }

  R operator()(Args... args) const { return call_(callable_, std::forward<Args>(args)...); }
  explicit operator bool() const noexcept { return call_ != nullptr; }

 private:
  void* callable_ = nullptr;
  R (*call_)(void*, Args...) = nullptr;
};

}  // namespace collide
