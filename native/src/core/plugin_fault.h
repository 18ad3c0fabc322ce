// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// No exception crosses from a plugin into its host. Each may carry its own copy of the C++
// runtime (a release links one into every binary, its symbols hidden: scripts/release/), and
// one copy's `catch` does not recognise the other's types, not even std::exception, so an
// exception thrown in the plugin would reach the host as an unknown one or end the process.
// The plugin's entries catch what the plugin throws and report it as a PluginFault; the host
// throws it again as its own exception of the same kind (throwPluginFault).
#include <new>
#include <string>
#include <type_traits>

#include "hyvox/errors.h"

namespace hyvox {

struct PluginFault {
    enum class Kind { None, InvalidInput, ResourceError, BackendError, Cancelled, OutOfMemory, Other };
    Kind kind = Kind::None;
    std::string message;
};

// The plugin's side: fn's result, or a default value with `fault` set to what fn threw. An
// exception the plugin's catch does not recognise came from the host (a callback of the job)
// and goes back as it is: its type is the host's own.
template <class Fn>
auto guardPluginCall(PluginFault& fault, Fn&& fn) -> decltype(fn()) {
    using Kind = PluginFault::Kind;
    auto report = [&](Kind kind, const char* message) {
        fault.kind = kind;
        fault.message = message;
    };
    try {
        return fn();
    } catch (const InvalidInput& e) {
        report(Kind::InvalidInput, e.what());
    } catch (const ResourceError& e) {
        report(Kind::ResourceError, e.what());
    } catch (const BackendError& e) {
        report(Kind::BackendError, e.what());
    } catch (const Cancelled& e) {
        report(Kind::Cancelled, e.what());
    } catch (const std::bad_alloc& e) {
        report(Kind::OutOfMemory, e.what());
    } catch (const std::exception& e) {
        report(Kind::Other, e.what());
    }
    if constexpr (!std::is_void_v<decltype(fn())>) return {};
}

// The host's side: throws the fault as the host's exception of its kind; nothing if none.
void throwPluginFault(const PluginFault& fault, const std::string& purpose);

}  // namespace hyvox
