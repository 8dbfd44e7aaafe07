// insitu/runtime/rank_stats.h - one stats record for an MPI job: every rank's record (totals
// and views) gathered on the root, where each pass's time becomes the slowest rank's (the
// mean beside it), each counter the sum over the ranks, and the bytes every rank sent on the
// step are listed (insitu/outputs/formats/stats_record.h, StatsRecord::Ranks). Collective: every
// rank calls it on the same steps.
#pragma once

#include <cstdint>

#include "insitu/outputs/formats/stats_record.h"
#include "insitu/parallel/communicator.h"

namespace voxspan {

// `bytes_sent`: what this rank sent on the step. On the root, `record` becomes the job's; on
// the other ranks it is left as it was.
void combine_rank_records(Communicator& comm, std::int64_t bytes_sent, StatsRecord& record);

}  // namespace voxspan
