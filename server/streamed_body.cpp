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
  if (taken_ > 0 && taken_ >= held_.size() / 2) {
    held_.erase(0, taken_);
    taken_ = 0;
  }
  read_ += size;
  if (dropping_) return true;
  held_.append(data, size);
  changed_.notify_all();
  // Before the answer starts: hold at the first bytes (the body's end needs no wait). After:
  // hold while ahead_bytes_ wait unread, unless the answer is being written (see the header).
  changed_.wait(lock, [this] {
    if (stopping_) return true;
    if (!open_) return read_ < first_bytes_ || read_ == source_.length;
    return writing_ || held_.size() - taken_ < ahead_bytes_;
  });
  return !stopping_;
}

std::size_t StreamedBody::wait_first() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return end_ != End::reading || read_ >= first_bytes_; });
  return (held_.size() - taken_) / record_bytes_;
}

void StreamedBody::open() {
  std::lock_guard lock(mutex_);
  open_ = true;
  changed_.notify_all();
}

std::size_t StreamedBody::take(std::size_t max_records, std::string& out) {
  std::unique_lock lock(mutex_);
  const std::size_t want = max_records * record_bytes_;
  changed_.wait(lock, [&] { return end_ != End::reading || held_.size() - taken_ >= want; });
  const std::size_t records = std::min(want, held_.size() - taken_) / record_bytes_;
  out.assign(held_, taken_, records * record_bytes_);
  taken_ += records * record_bytes_;
  changed_.notify_all();
  return records;
}

bool StreamedBody::drain() {
  std::unique_lock lock(mutex_);
  dropping_ = open_ = true;
  held_.clear();
  taken_ = 0;
  changed_.notify_all();
  changed_.wait(lock, [this] { return end_ != End::reading; });
  return end_ == End::whole;
}

void StreamedBody::writing(bool inside) {
  std::lock_guard lock(mutex_);
  writing_ = inside;
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
