// Test support: every DDS test runs loopback-only in a domain of its own, listed here so that no
// two tests share one (ctest runs them in parallel, each TEST in its own process).
#pragma once

#include <chrono>
#include <filesystem>
#include <string>

#include "smart/dds/domain.hpp"

namespace smart::test {

enum DomainId : int {
  kDomainCreateTwice = 101,
  kRoundTripAction = 102,
  kRoundTripProgress = 103,
  kRoundTripState = 104,
  kRoundTripClock = 105,
  kKeyedThousand = 106,
  kLateJoiner = 107,
  kDisposeState = 108,
  kListener = 109,
  kWaitSet = 110,
  kMatchedStatus = 111,
  kCrossProcessEcho = 112,
  kCrossProcessPing = 113,
  kLossyReliable = 114,
  kLossyBestEffort = 115,
  kDeadlineMissed = 116,
  kIncompatibleQos = 117,
  kRunExample = 120,
  kRunLockstep = 121,
  kRunKillSim = 122,
  kRunBadPlan = 123,
  kRunSeparate = 124,
  kRunGenerated = 125,
  kRunWarehouse500 = 126,
  kSimHostProtocol = 127,
  kRosPose = 128,
  kMixedRun = 129,
  kRunKillChild = 130,
  kLossyRunClean = 131,
  kLossyRun = 132,
  kRosView = 133,
  kFastDdsInterop = 134,
  kBenchRun = 135,
  kRosMap = 136,
  kResumeReference = 137,
  kResume = 138,
  kResumeNothing = 139,
  kMixedRestart = 140,
  kAgentNodeWindows = 141,
  kAgentNodeProgress = 142,
  kAgentNodeAccept = 143,
  kAgentI2cMissing = 144,
  kIsolationTwoRuns = 145,
  kIsolationNamedRuns = 146,
  kSimHostBadWindows = 147,
  kMonitorBadSamples = 148,
  kFaultsSecondMonitor = 149,
  kFaultsSecondMonitorAlone = 150,
  kFaultsRogue = 151,
  kFaultsRogueAlone = 152,
  kSecureRogue = 153,
  kSecurePlain = 154,
  kSecureViewer = 155,
  kAgentNodeRepublish = 156,
  kAgentNodeWeakMonitor = 157,
  kServeRuns = 158,
  kServeOpen = 159,
  kWebViewer = 160,  // web/test/viewer.test.mjs (SMART_DOMAIN in tests/CMakeLists.txt)
  kServeUpload = 161,
  kServeWatch = 162,
  kSecureWatch = 163,
  kRunShortStatus = 164,
  kExperiment = 165,  // and 166 (--jobs 2)
  kRunNoStates = 167,
  kRunStalls = 168,
  kAgentNodeLink = 169,
  kRunLink = 170,
  kExperimentCommand = 171,  // and 172 (--jobs 2)
  kRos2Fleet = 173,
  kRos2OdomAtStart = 174,
  kRosOdom = 175,
  kRosTwist = 176,
  kCalibrate = 177,
  kRosPlanView = 179,
  kDoctor = 180,
  kLabExample = 181,
  kRos2CalibrateTrim = 182,
  kRos2Doctor = 183,
  kDoctorHosts = 184,
  kDoctorMonitor = 185,
  kRunWideRobots = 186,
  kMultihostLockstep = 187,  // and 188: its one-host reference
  kMultihostMixed = 189,
  kMultihostLoss = 190,
  kMultihostCut = 191,
  kMultihostSecure = 192,
  kRunWalk = 193,
  kManyProcesses = 194,
  kShardedSmall = 195,
  kShardedWarehouse = 196,
  kShardedWarehouse1000 = 197,
  kShardedProcesses = 198,
  kShardedBadInput = 199,
  kMultihostSharded = 200,  // and 201: its one-host reference
  kAgentNodeShards = 203,
  kShardedSecure = 204,
  kShardPeerWriters = 205,
  kShardPeerClaims = 206,
  kListenerThrows = 207,
  kCommissioningDoctor = 208,
  kCommissioningTrim = 209,
  kRos2Calibrate = 178,
  kIntruderSimStatus = 210,
  kIntruderMonitorInfo = 211,
  kIntruderMidRun = 212,
  kIntruderResume = 213,
  kAdmissionFlood = 214,
  kParticipantDirectory = 215,
  kAdmissionOwnership = 216,
  kIntruderTicks = 217,
  kIntruderLeaves = 218,
  kServeHardening = 219,
  kIntruderWindows = 220,
  kIntruderProgress = 221,
  kAdmissionProof = 222,
  kRunKeyProve = 223,
  kRobotSpeakers = 224,
  kSecureInsider = 225,
  kServeRestart = 226,
  kPackagedAgent = 227,  // tests/packaging/packages_test.py (given on its command line)
  kLifelongLorr = 228,
  kLifelongSeed = 229,    // two runs one after the other
  kLifelongSecure = 118,  // three runs one after the other
  kLifelongMixed = 119,
  kMultihostLifelong = 202,  // the two-host run, then its one-host reference
  kLifelongRandom = 230,     // the last id --domain takes (Cyclone's port formula)
  // 101..230 are taken: later tests count down from 100.
  kLifelongPipePlanner = 100,
  kDdsPlanner = 99,          // tests/tools/dds_planner_test.cpp (its first TEST; below the rest)
  kPlannerNode = 98,         // tests/tools/planner_node_test.cpp (the same)
  kLifelongDdsPlanner = 97,  // the run, then its in-process reference
  kExperimentLifelong = 95,  // and 96 (--jobs 2)
  kLifelongLorrOutput = 94,
  kWebLifelong = 93,         // web/test/lifelong.test.mjs (given on its command line)
  kSwitchableRun = 92,       // and 91, 90: the plain run and the switchable run twice
  kSwitchableLifelong = 89,  // and 88, 87: the same for a lifelong run
  kWebSwitchable = 86,       // web/test/switchable.test.mjs (given on its command line)
  kRecordingReaders = 85,    // tests/readers/mcap.test.mjs (given on its command line)
  kRosViewNamespaces = 84,
  kFoxgloveBridge = 83,  // tests/readers/bridge.test.mjs (given on its command line)
  kShardJoin = 82,
  kPibtPlanRun = 81,
  kAdmissionListenerAttach = 79,
  kAdmissionLookupBeforeMade = 78,
  kSwitchableOptRun = 77,
  kLacamPlanRun = 76,
  kExperimentPlannerFails = 75,   // no run starts: the planner fails first
  kExperimentPlannerFloods = 74,  // the same
  kSwitchableLifelongOpt = 73,    // the switchable-opt run of kSwitchableLifelong
  kLifelongScratch = 72,
  kSwitchableCrossing = 71,           // its plain and switchable runs, one after the other
  kSwitchableLifelongLookahead = 70,  // the switchable-lookahead run of kSwitchableLifelong
  kShardPeerRepeats = 69,
  kSwitchableLifelongOneLocation = 68,  // kSwitchableLifelong's switchable run, no chains
  // One a TEST: ctest runs the TESTs of one file side by side too. kDdsPlanner and kPlannerNode
  // were shared by their files' TESTs, and two PlannerNode tests on one domain answered each
  // other's requests under ASan (2026-12-01).
  kPlannerNodeBadRequest = 67,
  kPlannerNodeOtherPlanner = 66,
  kPlannerNodeProblemGoes = 65,
  kDdsPlannerEarliest = 64,
  kDdsPlannerBadWindows = 63,
  kDdsPlannerLate = 62,
  kDdsPlannerForged = 61,
  kDdsPlannerLeaves = 60,
  // Shared by the TESTs of a file until scripts/check-test-domains.py (2026-12-01).
  kCalibrateTrim = 59,
  kCalibrateTrimAsk = 58,
  kCalibrateTrimSignal = 57,
  kBenchRunBadSize = 56,
  kIsolationBadName = 55,
  kLifelongBadFlags = 54,
  kRos2BadRobotLists = 53,
  kSwitchableResume = 52,
  kSwitchableResumeRun = 51,
  kSwitchableResumeMismatch = 50,
  kExperimentLookahead = 48,  // and 49 (--jobs 2)
  kExperimentWindowLns = 46,  // and 47 (--jobs 2)
  kExperimentPlanLns = 44,    // and 45 (--jobs 2)
};

// No test takes an id below this one: a test added under it moves it down. `smart experiment`'s
// default ids (campaign.hpp) stay below it, so a campaign beside `make test` shares no discovery
// with a test (CampaignDefaults.ItsDefaultDomainsStayBelowEveryTestsOwn).
constexpr int kLowestTestDomain = kExperimentPlanLns;

inline dds::DomainConfig loopback() { return dds::DomainConfig::loopback(); }

inline std::filesystem::path smart_exe() { return SMART_EXE; }

// How much slower this build's binaries run (4 under ASan + UBSan, tests/CMakeLists.txt): the
// factor of guards that wait for a hung child process, never of what a test asserts.
#ifndef SMART_SLOWDOWN
#define SMART_SLOWDOWN 1
#endif
constexpr int kSlowdown = SMART_SLOWDOWN;

// A path in the system temp folder for this test process; whatever is there is removed when the
// process exits (support/temp_cleanup.cpp; SMART_KEEP_TEST_FILES=1 keeps it).
inline std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("smart_test_" + std::to_string(::getpid()) + "_" + name);
}

}  // namespace smart::test
