#include "cosmo/trials/ros2_bag.hpp"

#include <sqlite3.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

namespace fs = std::filesystem;

namespace cosmo::trials {

namespace {

std::string withoutSlash(const std::string& topic) {
  return !topic.empty() && topic[0] == '/' ? topic.substr(1) : topic;
}

/// One open .db3 (read-only unless `write`), closed on destruction.
class Db {
 public:
  Db(const std::string& path, bool write) : path_(path) {
    const int flags = write ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE : SQLITE_OPEN_READONLY;
    if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
      const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      throw std::runtime_error(path + ": cannot open as sqlite3: " + why);
    }
  }
  ~Db() { sqlite3_close(db_); }
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;
  sqlite3* get() const { return db_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path_ + ": " + what + ": " + sqlite3_errmsg(db_));
  }
  void exec(const std::string& sql) const {
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, nullptr) != SQLITE_OK) fail(sql);
  }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

/// A prepared statement, finalized on destruction.
class Statement {
 public:
  Statement(const Db& db, const std::string& sql) : db_(&db) {
    if (sqlite3_prepare_v2(db.get(), sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      db.fail("not a ROS 2 bag (" + sql + ")");
  }
  ~Statement() { sqlite3_finalize(stmt_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  sqlite3_stmt* get() const { return stmt_; }
  /// sqlite3_step: true on a row, false when done, throws on an error.
  bool step() const {
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    db_->fail("reading messages");
  }
  std::string text(int col) const {
    const auto* t = sqlite3_column_text(stmt_, col);
    return t ? reinterpret_cast<const char*>(t) : "";
  }

 private:
  const Db* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

struct FileTopic {
  sqlite3_int64 id = -1;
  Ros2Topic topic;
};

std::vector<FileTopic> topicsOf(const Db& db) {
  Statement s(db,
              "SELECT t.id, t.name, t.type, t.serialization_format, "
              "(SELECT COUNT(*) FROM messages m WHERE m.topic_id = t.id) FROM topics t ORDER BY t.id");
  std::vector<FileTopic> out;
  while (s.step()) {
    FileTopic t;
    t.id = sqlite3_column_int64(s.get(), 0);
    t.topic.name = s.text(1);
    t.topic.type = s.text(2);
    t.topic.serialization_format = s.text(3);
    t.topic.messages = static_cast<std::size_t>(sqlite3_column_int64(s.get(), 4));
    out.push_back(std::move(t));
  }
  return out;
}

std::string topicList(const std::vector<Ros2Topic>& topics) {
  std::string s;
  for (const auto& t : topics) s += (s.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
  return s.empty() ? "none" : s;
}

}  // namespace

std::vector<std::string> ros2BagFiles(const std::string& bag_path) {
  if (!fs::exists(bag_path)) throw std::runtime_error(bag_path + ": no such file or folder");
  if (!fs::is_directory(bag_path)) return {bag_path};
  std::vector<std::string> files;
  const fs::path meta = fs::path(bag_path) / "metadata.yaml";
  if (fs::exists(meta)) {
    try {
      const YAML::Node info = YAML::LoadFile(meta.string())["rosbag2_bagfile_information"];
      if (!info) throw std::runtime_error("no rosbag2_bagfile_information");
      if (info["compression_format"] && !info["compression_format"].as<std::string>().empty())
        throw std::runtime_error("compressed ROS 2 bags (" + info["compression_format"].as<std::string>() +
                                 ") are not supported: decompress it with `ros2 bag convert`");
      if (info["storage_identifier"] && info["storage_identifier"].as<std::string>() != "sqlite3")
        throw std::runtime_error("storage " + info["storage_identifier"].as<std::string>() +
                                 " is not supported (sqlite3 only)");
      for (const auto& f : info["relative_file_paths"])
        files.push_back((fs::path(bag_path) / f.as<std::string>()).string());
    } catch (const YAML::Exception& e) {
      throw std::runtime_error(meta.string() + ": " + e.what());
    } catch (const std::runtime_error& e) { throw std::runtime_error(meta.string() + ": " + e.what()); }
  }
  if (files.empty()) {
    for (const auto& e : fs::directory_iterator(bag_path))
      if (e.path().extension() == ".db3") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
  }
  if (files.empty()) throw std::runtime_error(bag_path + ": a folder without .db3 files (not a ROS 2 bag)");
  for (const auto& f : files)
    if (!fs::exists(f)) throw std::runtime_error(bag_path + ": " + f + " listed in metadata.yaml does not exist");
  return files;
}

std::vector<Ros2Topic> listRos2Topics(const std::string& bag_path) {
  std::vector<Ros2Topic> topics;
  for (const auto& file : ros2BagFiles(bag_path)) {
    const Db db(file, false);
    for (const auto& ft : topicsOf(db)) {
      auto it = std::find_if(topics.begin(), topics.end(), [&](const Ros2Topic& t) { return t.name == ft.topic.name; });
      if (it == topics.end())
        topics.push_back(ft.topic);
      else
        it->messages += ft.topic.messages;
    }
  }
  return topics;
}

struct Ros2BagReader::Impl {
  std::vector<std::string> files;
  std::vector<sqlite3_int64> topic_ids;  ///< per file (-1: not in that file)
  Ros2Topic topic;
  std::string where;
  StampNs from = 0;
  std::size_t file = 0;
  std::unique_ptr<Db> db;
  std::unique_ptr<Statement> query;

  /// Opens the query of file `file` (skipping files without the topic); false past the last file.
  bool openFile() {
    query.reset();
    db.reset();
    for (; file < files.size(); ++file) {
      if (topic_ids[file] < 0) continue;
      db = std::make_unique<Db>(files[file], false);
      query = std::make_unique<Statement>(
          *db, "SELECT timestamp, data FROM messages WHERE topic_id = ? AND timestamp >= ? ORDER BY timestamp, id");
      sqlite3_bind_int64(query->get(), 1, topic_ids[file]);
      sqlite3_bind_int64(query->get(), 2, static_cast<sqlite3_int64>(from));
      return true;
    }
    return false;
  }
};

Ros2BagReader::Ros2BagReader(const std::string& bag_path, const std::string& topic) : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  I.files = ros2BagFiles(bag_path);
  I.where = bag_path + " " + topic;
  std::vector<Ros2Topic> all;
  for (const auto& file : I.files) {
    const Db db(file, false);
    sqlite3_int64 id = -1;
    for (const auto& ft : topicsOf(db)) {
      auto it = std::find_if(all.begin(), all.end(), [&](const Ros2Topic& t) { return t.name == ft.topic.name; });
      if (it == all.end())
        all.push_back(ft.topic);
      else
        it->messages += ft.topic.messages;
      if (withoutSlash(ft.topic.name) == withoutSlash(topic)) {
        id = ft.id;
        I.topic.name = ft.topic.name;
        I.topic.type = ft.topic.type;
        I.topic.serialization_format = ft.topic.serialization_format;
        I.topic.messages += ft.topic.messages;
      }
    }
    I.topic_ids.push_back(id);
  }
  if (I.topic.name.empty())
    throw std::runtime_error(bag_path + ": no topic " + topic + " in this ROS 2 bag; it has: " + topicList(all));
  if (I.topic.serialization_format != "cdr")
    throw std::runtime_error(I.where + ": serialization format '" + I.topic.serialization_format + "' is not cdr");
  if (I.topic.messages == 0) throw std::runtime_error(I.where + ": no messages on this topic");
  I.openFile();
}

Ros2BagReader::~Ros2BagReader() = default;

const Ros2Topic& Ros2BagReader::topic() const { return impl_->topic; }
const std::string& Ros2BagReader::where() const { return impl_->where; }

StampNs Ros2BagReader::lastReceived() const {
  StampNs last = 0;
  for (std::size_t f = 0; f < impl_->files.size(); ++f) {
    if (impl_->topic_ids[f] < 0) continue;
    const Db db(impl_->files[f], false);
    Statement s(db, "SELECT MAX(timestamp) FROM messages WHERE topic_id = ?");
    sqlite3_bind_int64(s.get(), 1, impl_->topic_ids[f]);
    if (s.step()) last = std::max(last, static_cast<StampNs>(sqlite3_column_int64(s.get(), 0)));
  }
  return last;
}

void Ros2BagReader::seek(StampNs received) {
  impl_->from = received;
  impl_->file = 0;
  impl_->openFile();
}

bool Ros2BagReader::next(Message& message) {
  Impl& I = *impl_;
  while (I.query) {
    if (I.query->step()) {
      sqlite3_stmt* s = I.query->get();
      message.received = static_cast<StampNs>(sqlite3_column_int64(s, 0));
      message.data = static_cast<const std::uint8_t*>(sqlite3_column_blob(s, 1));
      message.size = static_cast<std::size_t>(sqlite3_column_bytes(s, 1));
      return true;
    }
    ++I.file;
    I.openFile();
  }
  return false;
}

struct Ros2BagWriter::Impl {
  fs::path folder;
  std::string file_name;
  std::unique_ptr<Db> db;
  std::unique_ptr<Statement> insert;
  struct TopicInfo {
    std::string name, type;
    std::size_t messages = 0;
  };
  std::vector<TopicInfo> topics;
  StampNs first = 0, last = 0;
  std::size_t messages = 0;
};

Ros2BagWriter::Ros2BagWriter(const std::string& folder) : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  I.folder = fs::path(folder);
  std::string name = I.folder.filename().string();
  if (name.empty()) name = I.folder.parent_path().filename().string();
  I.file_name = name + "_0.db3";
  fs::create_directories(I.folder);
  const fs::path file = I.folder / I.file_name;
  std::error_code ec;
  fs::remove(file, ec);
  I.db = std::make_unique<Db>(file.string(), true);
  I.db->exec(
      "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
      "INSERT INTO schema VALUES (3, 'humble');"
      "CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, metadata TEXT NOT NULL);"
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
      "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, "
      "data BLOB NOT NULL);"
      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
      "BEGIN TRANSACTION;");
  I.insert = std::make_unique<Statement>(*I.db, "INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)");
}

Ros2BagWriter::~Ros2BagWriter() {
  try {
    close();
  } catch (...) {}
}

int Ros2BagWriter::addTopic(const std::string& name, const std::string& type) {
  Impl& I = *impl_;
  const int id = static_cast<int>(I.topics.size()) + 1;
  Statement s(*I.db,
              "INSERT INTO topics (id, name, type, serialization_format, offered_qos_profiles) "
              "VALUES (?, ?, ?, 'cdr', '')");
  sqlite3_bind_int(s.get(), 1, id);
  sqlite3_bind_text(s.get(), 2, name.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(s.get(), 3, type.c_str(), -1, SQLITE_TRANSIENT);
  s.step();
  I.topics.push_back({name, type, 0});
  return id;
}

void Ros2BagWriter::write(int topic, StampNs received, const std::vector<std::uint8_t>& cdr) {
  Impl& I = *impl_;
  if (!I.insert) throw std::runtime_error(I.folder.string() + ": bag already closed");
  if (topic < 1 || topic > static_cast<int>(I.topics.size()))
    throw std::invalid_argument(I.folder.string() + ": unknown topic id " + std::to_string(topic));
  sqlite3_stmt* s = I.insert->get();
  sqlite3_reset(s);
  sqlite3_bind_int(s, 1, topic);
  sqlite3_bind_int64(s, 2, static_cast<sqlite3_int64>(received));
  sqlite3_bind_blob64(s, 3, cdr.data(), cdr.size(), SQLITE_STATIC);
  I.insert->step();
  I.first = I.messages == 0 ? received : std::min(I.first, received);
  I.last = std::max(I.last, received);
  ++I.messages;
  ++I.topics[topic - 1].messages;
}

void Ros2BagWriter::close() {
  Impl& I = *impl_;
  if (!I.db) return;
  I.insert.reset();
  I.db->exec("COMMIT;");
  I.db.reset();
  const StampNs duration = I.messages ? I.last - I.first : 0;
  std::ofstream out(I.folder / "metadata.yaml");
  out << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
      << "  duration:\n    nanoseconds: " << duration << "\n"
      << "  starting_time:\n    nanoseconds_since_epoch: " << I.first << "\n"
      << "  message_count: " << I.messages << "\n  topics_with_message_count:\n";
  for (const auto& t : I.topics)
    out << "    - topic_metadata:\n        name: " << t.name << "\n        type: " << t.type
        << "\n        serialization_format: cdr\n        offered_qos_profiles: \"\"\n      message_count: "
        << t.messages << "\n";
  out << "  compression_format: \"\"\n  compression_mode: \"\"\n  relative_file_paths:\n    - " << I.file_name << "\n"
      << "  files:\n    - path: " << I.file_name
      << "\n      starting_time:\n        nanoseconds_since_epoch: " << I.first
      << "\n      duration:\n        nanoseconds: " << duration << "\n      message_count: " << I.messages << "\n";
  if (!out) throw std::runtime_error((I.folder / "metadata.yaml").string() + ": write failed");
}

}  // namespace cosmo::trials
