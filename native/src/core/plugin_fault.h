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
#include <utility>

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

// The plugin's entry for function Fn: Fn's parameters and a PluginFault& last, reporting in
// it what Fn throws (`guardedEntry<&runHybridBackend>` in the plugin's table).
template <auto Fn>
struct GuardedEntry;
template <class R, class... Params, R (*Fn)(Params...)>
struct GuardedEntry<Fn> {
    static R call(Params... params, PluginFault& fault) {
        return guardPluginCall(fault, [&]() -> R { return Fn(params...); });
    }
};
template <auto Fn>
constexpr auto guardedEntry = &GuardedEntry<Fn>::call;

// The host's side: throws the fault as the host's exception of its kind; nothing if none.
void throwPluginFault(const PluginFault& fault, const std::string& purpose);

// The host's call of a guarded entry: its result, or the fault it reported thrown as the
// host's exception.
template <class Entry, class... Args>
auto callPlugin(const std::string& purpose, Entry entry, Args&&... args) {
    PluginFault fault;
    if constexpr (std::is_void_v<std::invoke_result_t<Entry, Args..., PluginFault&>>) {
        entry(std::forward<Args>(args)..., fault);
        throwPluginFault(fault, purpose);
    } else {
        auto result = entry(std::forward<Args>(args)..., fault);
        throwPluginFault(fault, purpose);
        return result;
    }
}

}  // namespace hyvox
