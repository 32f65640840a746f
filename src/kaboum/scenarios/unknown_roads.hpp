// Generator of a navigation problem with n independent unknown roads (the scaling instance of
// docs/benchmarks.md, "Knowledge representations"): a vehicle drives a one-way route of n legs;
// each leg has a direct road that may be blocked, which it can observe from the leg's start, and a
// known-clear detour through a side place. 2^n initial worlds, no correlation between them.
#pragma once

#include <string>

namespace kaboum::scenarios {

// Contingent PDDL domain (independent of n): sense-road observes Kw(clear r) at the road's start;
// drive needs K(clear r).
std::string unknownRoadsDomain();
// Problem for n >= 1 legs: places l0..ln and s1..sn, roads ri: l(i-1) -> li of unknown state and
// detours ai: l(i-1) -> si, bi: si -> li known clear; I = K(at l0); G = K(at ln).
std::string unknownRoadsProblem(int n);

}  // namespace kaboum::scenarios
