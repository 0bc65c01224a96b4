// A helper program for the scheduling tests: applies PolicyRequest::kAuto in a fresh thread and
// prints what it got, so that a test can run it with capabilities dropped (under setpriv).

#include <chrono>
#include <iostream>
#include <thread>

#include "grip/platform/scheduling.hpp"

int main() {
  using grip::platform::PolicyRequest;
  grip::platform::SchedulingRequest request;
  request.request = PolicyRequest::kAuto;
  request.runtime = std::chrono::milliseconds(2);
  request.deadline = std::chrono::milliseconds(10);
  request.period = std::chrono::milliseconds(10);
  int status = 0;
  // A fresh thread, so that the main thread stays SCHED_OTHER whatever is granted.
  std::thread probe([&] {
    const auto outcome = grip::platform::apply_scheduling(request);
    if (!outcome) {
      std::cout << "GRIP_PROBE error=" << outcome.error().message << "\n";
      status = 1;
      return;
    }
    std::cout << "GRIP_PROBE policy=" << grip::platform::policy_name(outcome->policy) << "\n"
              << "GRIP_PROBE reason=" << outcome->fallback_reason << "\n"
              << "GRIP_PROBE current="
              << grip::platform::policy_name(grip::platform::current_policy()) << "\n";
  });
  probe.join();
  return status;
}
