// Contract: a lifelong run's tasks as the viewer draws them (GET /api/runs/{id}/tasks): every
// task with its robot, its errand cells, when it was revealed, assigned and finished and when
// each errand was done, and the tasks-finished curve with the last minute's throughput. Pure:
// the results files' text in (tasks.csv, events.csv, throughput.csv: results_format.hpp), JSON
// out. The files may come from an upload: a malformed one throws std::invalid_argument naming
// the file and line (results_format's readers), an errand past its task's errands is skipped.
// While a run goes, tasks.csv holds only its finished tasks: the others come from events.csv
// (revealed, with their cells; assigned; errands done).
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

namespace smart::serve {

// {"tasks": [{"id", "robot" (null: never assigned), "revealed_s", "assigned_s", "finished_s"
//   (null: not yet), "cells": [[x, y], ...], "done_s": [per errand done, in order]}],
//  "throughput": {"t_s": [...], "finished": [...], "last_min": [...]}}, tasks by id.
nlohmann::json task_timeline(std::string_view tasks_csv, std::string_view events_csv,
                             std::string_view throughput_csv);

}  // namespace smart::serve
