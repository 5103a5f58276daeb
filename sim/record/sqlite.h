// A thin RAII layer over SQLite's C API for objects.sqlite: a connection, prepared statements
// with bound parameters, and errors as exceptions that name the file. Nothing here knows the
// schema (object_schema.h does).
#pragma once

#include <concepts>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

struct sqlite3;
struct sqlite3_stmt;

namespace occsim::sql {

// Any failure of SQLite; what() is "<file>: <what was done>: <SQLite's message>". `code` is
// SQLite's primary result code (SQLITE_CORRUPT, SQLITE_NOTADB, ...).
struct Error : std::runtime_error {
    Error(const std::string& what, int result_code) : std::runtime_error(what), code(result_code) {}
    int code;
};

class Statement;

class Database {
  public:
    enum class Mode { Create, ReadOnly };
    // Create replaces nothing: the caller removes an old file first. Throws Error.
    Database(const std::filesystem::path& file, Mode mode);
    ~Database();
    Database(const Database&) = delete;
    Database& operator=(const Database&) = delete;

    void exec(std::string_view sql);  // one or more statements without parameters
    Statement prepare(std::string_view sql);
    void close();  // throws Error when SQLite cannot finish writing
    const std::filesystem::path& file() const { return file_; }
    sqlite3* handle() const { return db_; }
    [[noreturn]] void fail(const std::string& doing, int code) const;

  private:
    std::filesystem::path file_;
    sqlite3* db_ = nullptr;
};

// A prepared statement: bind from 1, step, read columns from 0. reset() makes it reusable with
// new bindings (the steady state of an insert loop allocates nothing).
class Statement {
  public:
    Statement(Database& db, sqlite3_stmt* stmt) : db_(&db), stmt_(stmt) {}
    ~Statement();
    Statement(Statement&& other) noexcept;
    Statement& operator=(Statement&&) = delete;
    Statement(const Statement&) = delete;

    template <std::integral T>
    Statement& bind(int index, T value) {
        return bindInteger(index, static_cast<int64_t>(value));
    }
    Statement& bindInteger(int index, int64_t value);
    Statement& bind(int index, double value);
    Statement& bind(int index, std::string_view text);
    Statement& bindNull(int index);
    template <class T>
    Statement& bind(int index, const std::optional<T>& value) {
        return value ? bind(index, *value) : bindNull(index);
    }
    // True while there is a row to read; false once done. Throws Error.
    bool step();
    void run() { step(); }  // for statements that return no row
    void reset();

    int64_t integer(int column) const;
    double real(int column) const;
    std::string text(int column) const;
    bool isNull(int column) const;

  private:
    Database* db_;
    sqlite3_stmt* stmt_;
};

}  // namespace occsim::sql
