#include "streamed_body.hpp"

#include <algorithm>

namespace footpoint::server {

StreamedBody::StreamedBody(BodySource source, std::size_t record_bytes, std::size_t first_bytes,
                           std::size_t ahead_bytes)
    : source_(std::move(source)),
      record_bytes_(record_bytes),
      first_bytes_(first_bytes),
      ahead_bytes_(std::max(ahead_bytes, record_bytes)) {
  reader_ = std::thread([this] {
    const bool whole =
        source_.read([this](const char* data, std::size_t size) { return receive(data, size); });
    std::lock_guard lock(mutex_);
    end_ = stopping_ ? End::stopped : whole && read_ == source_.length ? End::whole : End::short_body;
    changed_.notify_all();
  });
}

StreamedBody::~StreamedBody() { stop(); }

bool StreamedBody::receive(const char* data, std::size_t size) {
  std::unique_lock lock(mutex_);
  if (stopping_) return false;
  read_ += size;
  if (dropping_) return true;
  while (size > 0) {
    if (blocks_.empty() || blocks_.back().size() == kBlock) {
      blocks_.emplace_back();
      blocks_.back().reserve(kBlock);
    }
    const std::size_t part = std::min(size, kBlock - blocks_.back().size());
    blocks_.back().append(data, part);
    data += part;
    size -= part;
    held_ += part;
  }
  changed_.notify_all();
  // Before the answer starts: hold at the first bytes (the body's end needs no wait). After:
  // hold while ahead_bytes_ wait unread, unless a write of the answer has stalled (see the header).
  while (!stopping_) {
    if (!open_) {
      if (read_ < first_bytes_ || read_ == source_.length) break;
      changed_.wait(lock);
    } else if (held_ < ahead_bytes_) {
      break;
    } else if (writing_) {
      const auto stalled = write_start_ + kStall;
      if (std::chrono::steady_clock::now() >= stalled) break;
      changed_.wait_until(lock, stalled);
    } else {
      changed_.wait(lock);
    }
  }
  return !stopping_;
}

void StreamedBody::copy_front(std::size_t bytes, std::string& out, bool drop) {
  std::size_t block = 0, at = front_at_;
  const std::size_t copied = bytes;
  while (bytes > 0) {
    const std::size_t part = std::min(bytes, blocks_[block].size() - at);
    out.append(blocks_[block], at, part);
    bytes -= part;
    at += part;
    if (at == blocks_[block].size()) {
      ++block;
      at = 0;
    }
  }
  if (!drop) return;
  held_ -= copied;
  blocks_.erase(blocks_.begin(), blocks_.begin() + static_cast<std::ptrdiff_t>(block));
  front_at_ = at;
}

std::size_t StreamedBody::wait_first(std::string& out) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return end_ != End::reading || read_ >= first_bytes_; });
  const std::size_t records = held_ / record_bytes_;
  out.clear();
  copy_front(records * record_bytes_, out, false);
  return records;
}

void StreamedBody::open() {
  std::lock_guard lock(mutex_);
  open_ = true;
  changed_.notify_all();
}

std::size_t StreamedBody::take(std::size_t max_records, std::string& out) {
  std::unique_lock lock(mutex_);
  const std::size_t want = max_records * record_bytes_;
  changed_.wait(lock, [&] { return end_ != End::reading || held_ >= want; });
  const std::size_t records = std::min(want, held_) / record_bytes_;
  out.clear();
  copy_front(records * record_bytes_, out, true);
  changed_.notify_all();
  return records;
}

bool StreamedBody::drain() {
  std::unique_lock lock(mutex_);
  dropping_ = open_ = true;
  blocks_.clear();
  front_at_ = held_ = 0;
  changed_.notify_all();
  changed_.wait(lock, [this] { return end_ != End::reading; });
  return end_ == End::whole;
}

void StreamedBody::writing(bool inside) {
  std::lock_guard lock(mutex_);
  writing_ = inside;
  write_start_ = std::chrono::steady_clock::now();
  changed_.notify_all();
}

void StreamedBody::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    changed_.notify_all();
  }
  if (reader_.joinable()) reader_.join();
}

StreamedBody::End StreamedBody::end() const {
  std::lock_guard lock(mutex_);
  return end_;
}

std::size_t StreamedBody::bytes_read() const {
  std::lock_guard lock(mutex_);
  return read_;
}

}  // namespace footpoint::server
