// The results folder's format: every row written and read back, numbers as %.10g, empty fields as
// "not known", and readers that name the file and line of a bad row.
#include "smart/monitor/results_format.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace smart::results {
namespace {

using ::testing::HasSubstr;

// What a reader throws, or "accepted".
template <class Read>
std::string message(Read read) {
  try {
    read();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

std::string with_header(std::string_view header, const std::string& rows) {
  return std::string(header) + "\n" + rows;
}

TEST(ResultsFormat, RobotRowsRoundTripAndEmptyFieldsAreNotKnown) {
  std::string text;
  append_row(text, RobotRow{0, 12.5, 3.25, 2, 14, 9.0});
  append_row(text, RobotRow{1, std::nullopt, 0.1, 0, 3, std::nullopt});
  EXPECT_EQ(text, "0,12.5,3.25,2,14,9\n1,,0.1,0,3,\n");
  const auto rows = parse_robots_csv(with_header(kRobotsHeader, text));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].finish_time_s, 12.5);
  EXPECT_EQ(rows[0].lower_bound_s, 9.0);
  EXPECT_EQ(rows[1].robot, 1u);
  EXPECT_FALSE(rows[1].finish_time_s.has_value());
  EXPECT_FALSE(rows[1].lower_bound_s.has_value());
  EXPECT_EQ(rows[1].actions, 3u);
}

TEST(ResultsFormat, NumbersAreWrittenAsPrintfsTenDigitG) {
  for (const double v : {1.0 / 3.0, 1234567.891234, 1e-7, 0.1 + 0.2, 487.29999999999}) {
    std::string text;
    append_row(text, StateRow{v, 3, v, -v, 0, 0, 0, 0, 0, 7});
    char expected[64];
    std::snprintf(expected, sizeof expected, "%.10g,3,%.10g,%.10g,", v, v, -v);
    EXPECT_EQ(text.substr(0, std::string(expected).size()), expected) << v;
  }
}

TEST(ResultsFormat, ActionRowsRoundTripWithTheirLineNumbers) {
  std::string text;
  append_row(text, ActionRow{2, 0, ActionType::kRotate, 0.5});
  append_row(text, ActionRow{2, 1, ActionType::kMove, std::nullopt});
  EXPECT_EQ(text, "2,0,rotate,0.5\n2,1,move,\n");
  std::vector<std::pair<ActionRow, std::size_t>> read;
  for_each_action_row(with_header(kActionsHeader, text),
                      [&](const ActionRow& r, std::size_t line) { read.emplace_back(r, line); });
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].first.type, ActionType::kRotate);
  EXPECT_EQ(read[0].first.finish_time_s, 0.5);
  EXPECT_EQ(read[0].second, 2u);
  EXPECT_EQ(read[1].first.action, 1u);
  EXPECT_FALSE(read[1].first.finish_time_s.has_value());
}

TEST(ResultsFormat, StateRowsRoundTripAndOlderFilesWithoutTheLastColumnsRead) {
  std::string text;
  const StateRow s{0.1, 4, 1.5, 2.5, 3.14, 0.2, -0.1, 0.19, 0.21, 6};
  append_row(text, s);
  EXPECT_EQ(text, "0.1,4,1.5,2.5,3.14,0.2,-0.1,0.19,0.21,6\n");
  std::vector<StateRow> rows;
  for_each_state_row(with_header(kStatesHeader, text + "0.2,1,1,2,0\n"),
                     [&](const StateRow& r) { rows.push_back(r); });
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].queue, 6u);
  EXPECT_EQ(rows[0].right_mps, 0.21);
  EXPECT_EQ(rows[1].robot, 1u);
  EXPECT_EQ(rows[1].queue, 0u) << "a pose-only row of an older file";
  EXPECT_FALSE(parse_state_line("0.3,1,1,2").has_value()) << "a live file's partial line";
}

TEST(ResultsFormat, BadRowsNameTheFileTheLineAndWhatARowHolds) {
  EXPECT_THAT(message([] { parse_robots_csv("h\n0,1,2,3,4,5\n1,soon,2,3,4,5\n"); }),
              HasSubstr("robots.csv line 3: expected robot,finish_time_s,waiting_time_s"));
  EXPECT_THAT(message([] { parse_robots_csv("h\n0,1,2,3,4,5,6\n"); }), HasSubstr("line 2"));
  EXPECT_THAT(message([] { for_each_action_row("h\n0,0,jump,1\n", [](auto&, auto) {}); }),
              HasSubstr("actions.csv line 2: expected robot,action,move|rotate"));
  EXPECT_THAT(message([] { for_each_action_row("h\n0,0,move,-1\n", [](auto&, auto) {}); }),
              HasSubstr("actions.csv line 2"));
  EXPECT_THAT(message([] { for_each_state_row("h\n\n0,-1,0,0,0\n", [](auto&) {}); }),
              HasSubstr("states.csv line 3"));
  EXPECT_THAT(message([] { for_each_state_row("h\n0,1,nan,0,0\n", [](auto&) {}); }),
              HasSubstr("states.csv line 2"));
}

TEST(ResultsFormat, OnlyTheFolderFilesAreResultsFiles) {
  for (const auto f : kFiles) EXPECT_TRUE(is_results_file(f)) << f;
  EXPECT_FALSE(is_results_file("run.out"));
  EXPECT_FALSE(is_results_file("../summary.json"));
  EXPECT_EQ(sim_report_name(3), "sim-3.json");
}

TEST(ResultsFormat, ASimReportIsItsLastJsonLineAndABadOneNamesTheFileAndKey) {
  const auto r = parse_sim_report(
      "{\"ok\":false}\n{\"ok\":true,\"error\":\"\",\"sim_time_s\":12.5,"
      "\"robot_contacts\":7,\"wall_contacts\":1,\"handovers_in\":3}\n\n",
      "sim-0.json");
  EXPECT_TRUE(r.ok);
  EXPECT_DOUBLE_EQ(r.sim_time_s, 12.5);
  EXPECT_EQ(r.robot_contacts, 7u);
  EXPECT_EQ(r.wall_contacts, 1u);
  EXPECT_EQ(r.handovers_in, 3u);
  EXPECT_THAT(message([] { parse_sim_report("", "sim-1.json"); }),
              HasSubstr("sim-1.json: no sim report"));
  EXPECT_THAT(message([] { parse_sim_report("{\"ok\":true,\"sim_time_s\":1}", "s.json"); }),
              HasSubstr("s.json: sim report key \"robot_contacts\" is missing"));
  EXPECT_THAT(message([] {
                parse_sim_report(
                    R"({"ok":true,"sim_time_s":1,"robot_contacts":-2,"wall_contacts":0})",
                    "s.json");
              }),
              HasSubstr("\"robot_contacts\" is missing or of the wrong type"));
}

// progress.csv is read while it is written: the last complete row counts, a torn one does not.
TEST(ResultsFormat, TheLastCompleteProgressRowOfAGrowingFile) {
  std::string text(kProgressHeader);
  text += "\n";
  EXPECT_FALSE(last_progress_row(text));  // the header alone
  append_row(text, ProgressRow{1.5, 3, 40});
  append_row(text, ProgressRow{2.25, 7, 40});
  auto r = last_progress_row(text);
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->t_s, 2.25);
  EXPECT_EQ(r->finished, 7u);
  EXPECT_EQ(r->total, 40u);
  EXPECT_EQ(last_progress_row(text + "3.0,9")->finished, 7u);  // a partial last line waits
  EXPECT_EQ(last_progress_row(text.substr(text.find('\n', 5) - 3))->finished, 7u);  // a tail
  EXPECT_FALSE(last_progress_row("1.0,50,40\n"));  // more finished than there are
  EXPECT_FALSE(last_progress_row(""));
}

// finished.csv: each robot's count, whole or not at all (a torn file reads as nothing).
TEST(ResultsFormat, FinishedCountsRoundTripAndATornFileIsNothing) {
  const std::vector<uint32_t> counts{3, 0, 17};
  const auto text = finished_csv(counts);
  EXPECT_EQ(text, "robot,finished\n0,3\n1,0\n2,17\n");
  EXPECT_EQ(parse_finished_csv(text), counts);
  EXPECT_TRUE(parse_finished_csv(text.substr(0, text.size() - 3)).empty());  // "2," torn
  EXPECT_TRUE(parse_finished_csv("robot,finished\n0,3\n2,5\n").empty());     // robot 1 missing
  EXPECT_TRUE(parse_finished_csv("t_s,finished,total\n1,2,3\n").empty());
  EXPECT_TRUE(parse_finished_csv("").empty());
}

TEST(ResultsFormat, LifelongTaskAndThroughputRowsRoundTrip) {
  std::string tasks(kTasksHeader);
  tasks += '\n';
  append_row(tasks, TaskRow{3, 1, 7u, 2, 2, 0.5, 0.5, 4.25, 9.75, {{4, 7}, {12, 0}}});
  append_row(tasks, TaskRow{4, 2, std::nullopt, 1, 0, 1, std::nullopt, std::nullopt, std::nullopt});
  EXPECT_NE(tasks.find("3,1,7,2,2,0.5,0.5,4.25,9.75,9.25,4 7;12 0\n"), std::string::npos) << tasks;
  const auto rows = parse_tasks_csv(tasks);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].robot, 7u);
  EXPECT_EQ(rows[0].cells, (std::vector<std::pair<int32_t, int32_t>>{{4, 7}, {12, 0}}));
  EXPECT_TRUE(rows[1].cells.empty());
  EXPECT_EQ(rows[0].finished_s, 9.75);
  EXPECT_FALSE(rows[1].robot.has_value());
  EXPECT_FALSE(rows[1].assigned_s.has_value());
  std::string thr(kThroughputHeader);
  thr += '\n';
  append_row(thr, ThroughputRow{60, 12, 12, 1.5, 800, 40});
  const auto t = parse_throughput_csv(thr);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].kept_actions, 800u);
  std::string ev;
  append_row(ev, EventRow{2.5, "refused", std::nullopt, 3u, std::nullopt, "a, b\nc"});
  EXPECT_EQ(ev, "2.5,refused,,3,,a; b c\n");
  EXPECT_THROW(parse_tasks_csv(std::string(kTasksHeader) + "\n1,2,x,1,0,0,,,,,\n"),
               std::invalid_argument);
  for (const char* cells : {"4", "4 x", "4 7;", "4 7 8", "4;7"}) {
    EXPECT_THROW(parse_tasks_csv(std::string(kTasksHeader) + "\n1,2,,1,0,0,,,,," + cells + "\n"),
                 std::invalid_argument)
        << cells;
  }
}

// switches.csv (issue 29): written and read by one definition; a bad row names its line. The
// entering actions' seqs may be empty (not recorded); files written before them and the
// anticipated column have five columns.
TEST(ResultsFormat, SwitchRowsRoundTripAndABadRowNamesItsLine) {
  std::string csv(kSwitchesHeader);
  csv += '\n';
  append_row(csv, SwitchRow{12.25, 3, 4.5, 7, 2, 40, 38, true});
  append_row(csv, SwitchRow{13.5, 1, 0, 2, 7, {}, {}, false});
  EXPECT_EQ(csv,
            "time_s,x,y,first,second,first_seq,second_seq,anticipated\n"
            "12.25,3,4.5,7,2,40,38,1\n13.5,1,0,2,7,,,0\n");
  const auto rows = parse_switches_csv(csv + "14,2,2,1,3\n");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].y, 4.5);
  EXPECT_EQ(rows[0].first, 7u);
  EXPECT_EQ(rows[0].second, 2u);
  EXPECT_EQ(rows[0].first_seq, 40u);
  EXPECT_EQ(rows[0].second_seq, 38u);
  EXPECT_TRUE(rows[0].anticipated);
  EXPECT_FALSE(rows[1].first_seq || rows[1].second_seq || rows[1].anticipated);
  EXPECT_FALSE(rows[2].first_seq || rows[2].second_seq || rows[2].anticipated);
  EXPECT_EQ(rows[2].second, 3u);
  for (const char* bad :
       {"1,2,3,4\n", "1,2,3,4,x\n", "-1,2,3,4,5\n", "1,nan,3,4,5\n", "1,2,3,4,5,6\n",
        "1,2,3,4,5,6,7\n", "1,2,3,4,5,6,7,0,0\n", "1,2,3,4,5,-6,7,0\n", "1,2,3,4,5,6,x,0\n",
        "1,2,3,4,5,6,7,2\n", "1,2,3,4,5,6,7,\n"}) {
    try {
      (void)parse_switches_csv(csv + bad);
      ADD_FAILURE() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("switches.csv line 4")) << bad;
    }
  }
}

}  // namespace
}  // namespace smart::results
