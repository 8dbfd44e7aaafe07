#include "insitu/parallel/communicator.h"

#include <mpi.h>

#include <algorithm>
#include <climits>

#include "voxspan/error.h"

namespace voxspan {
namespace {

void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw make_error("MPI ", what, " failed: ", std::string(text, std::size_t(length)));
}

int as_count(std::size_t n, const char* what) {
  if (n > std::size_t(INT_MAX)) throw make_error("MPI ", what, ": ", n, " bytes exceed an int");
  return static_cast<int>(n);
}

}  // namespace

struct Communicator::Handles {
  MPI_Comm comm = MPI_COMM_NULL;  // a duplicate: our messages never meet the solver's
  ~Handles() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized && comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
  }
};

Communicator::Communicator(int fortran_handle) : mpi_(std::make_unique<Handles>()) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized)
    throw make_error(
        "an MPI communicator was given but MPI is not initialized (call MPI_Init "
        "before making the adapter)");
  const MPI_Comm given = MPI_Comm_f2c(static_cast<MPI_Fint>(fortran_handle));
  check(MPI_Comm_dup(given, &mpi_->comm), "Comm_dup");
  MPI_Comm_rank(mpi_->comm, &rank_);
  MPI_Comm_size(mpi_->comm, &size_);
  MPI_Comm node = MPI_COMM_NULL;
  check(MPI_Comm_split_type(mpi_->comm, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node),
        "Comm_split_type");
  MPI_Comm_rank(node, &node_rank_);
  MPI_Comm_size(node, &node_size_);
  MPI_Comm_free(&node);
}

Communicator::~Communicator() = default;

Agreement Communicator::agree(bool ok, const std::string& message) {
  // The lowest failing rank, or size_ when none failed.
  int mine = ok ? size_ : rank_, first = size_;
  check(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, mpi_->comm), "Allreduce");
  bytes_sent_ += sizeof(int);
  if (first == size_) return {};
  return {false, first, broadcast(rank_ == first ? message : std::string(), first)};
}

void Communicator::agree_or_throw(bool ok, const std::string& message) {
  const Agreement agreed = agree(ok, message);
  if (agreed.ok) return;
  if (size_ == 1) throw Error(agreed.message);
  throw make_error("rank ", agreed.rank, ": ", agreed.message);
}

void Communicator::min(std::span<double> v) {
  check(MPI_Allreduce(MPI_IN_PLACE, v.data(), as_count(v.size(), "min"), MPI_DOUBLE, MPI_MIN,
                      mpi_->comm),
        "Allreduce");
  bytes_sent_ += std::int64_t(v.size_bytes());
}

void Communicator::sum(std::span<double> v) {
  check(MPI_Allreduce(MPI_IN_PLACE, v.data(), as_count(v.size(), "sum"), MPI_DOUBLE, MPI_SUM,
                      mpi_->comm),
        "Allreduce");
  bytes_sent_ += std::int64_t(v.size_bytes());
}

void Communicator::max(std::span<double> v) {
  check(MPI_Allreduce(MPI_IN_PLACE, v.data(), as_count(v.size(), "max"), MPI_DOUBLE, MPI_MAX,
                      mpi_->comm),
        "Allreduce");
  bytes_sent_ += std::int64_t(v.size_bytes());
}

void Communicator::sum(std::span<std::int64_t> v) {
  check(MPI_Allreduce(MPI_IN_PLACE, v.data(), as_count(v.size(), "sum"), MPI_INT64_T, MPI_SUM,
                      mpi_->comm),
        "Allreduce");
  bytes_sent_ += std::int64_t(v.size_bytes());
}

std::string Communicator::broadcast(const std::string& text, int root) {
  int length = as_count(text.size(), "broadcast");
  check(MPI_Bcast(&length, 1, MPI_INT, root, mpi_->comm), "Bcast");
  std::string out = rank_ == root ? text : std::string(std::size_t(length), '\0');
  check(MPI_Bcast(out.data(), length, MPI_CHAR, root, mpi_->comm), "Bcast");
  if (rank_ == root) bytes_sent_ += std::int64_t(sizeof(int) + text.size());
  return out;
}

void Communicator::broadcast(std::span<std::byte> bytes, int root) {
  check(MPI_Bcast(bytes.data(), as_count(bytes.size(), "broadcast"), MPI_BYTE, root, mpi_->comm),
        "Bcast");
  if (rank_ == root) bytes_sent_ += std::int64_t(bytes.size());
}

std::vector<std::vector<std::byte>> Communicator::gather(std::span<const std::byte> bytes,
                                                         int root) {
  const int mine = as_count(bytes.size(), "gather");
  std::vector<int> counts(rank_ == root ? std::size_t(size_) : 0);
  check(MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, root, mpi_->comm), "Gather");
  std::vector<int> offsets(counts.size(), 0);
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    offsets[r] = as_count(total, "gather");
    total += std::size_t(counts[r]);
  }
  std::vector<std::byte> all(total);
  check(MPI_Gatherv(bytes.data(), mine, MPI_BYTE, all.data(), counts.data(), offsets.data(),
                    MPI_BYTE, root, mpi_->comm),
        "Gatherv");
  bytes_sent_ += std::int64_t(sizeof(int)) + (rank_ == root ? 0 : mine);
  std::vector<std::vector<std::byte>> out(counts.size());
  for (std::size_t r = 0; r < counts.size(); ++r)
    out[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
  return out;
}

std::vector<std::vector<std::byte>> Communicator::exchange(
    const std::vector<std::vector<std::byte>>& send) {
  if (send.size() != std::size_t(size_))
    throw make_error("MPI exchange: ", send.size(), " parts for ", size_, " ranks");
  std::vector<int> send_counts(send.size()), recv_counts(send.size());
  for (std::size_t r = 0; r < send.size(); ++r)
    send_counts[r] = as_count(send[r].size(), "exchange");
  check(MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, mpi_->comm),
        "Alltoall");
  std::vector<int> send_offsets(send.size()), recv_offsets(send.size());
  std::size_t send_total = 0, recv_total = 0;
  for (std::size_t r = 0; r < send.size(); ++r) {
    send_offsets[r] = as_count(send_total, "exchange");
    recv_offsets[r] = as_count(recv_total, "exchange");
    send_total += std::size_t(send_counts[r]);
    recv_total += std::size_t(recv_counts[r]);
  }
  std::vector<std::byte> out_bytes(send_total), in_bytes(recv_total);
  for (std::size_t r = 0; r < send.size(); ++r)
    std::copy(send[r].begin(), send[r].end(), out_bytes.begin() + send_offsets[r]);
  check(
      MPI_Alltoallv(out_bytes.data(), send_counts.data(), send_offsets.data(), MPI_BYTE,
                    in_bytes.data(), recv_counts.data(), recv_offsets.data(), MPI_BYTE, mpi_->comm),
      "Alltoallv");
  bytes_sent_ += std::int64_t(sizeof(int)) * (size_ - 1) +
                 std::int64_t(send_total - send[std::size_t(rank_)].size());
  std::vector<std::vector<std::byte>> received(send.size());
  for (std::size_t r = 0; r < send.size(); ++r)
    received[r].assign(in_bytes.begin() + recv_offsets[r],
                       in_bytes.begin() + recv_offsets[r] + recv_counts[r]);
  return received;
}

}  // namespace voxspan
