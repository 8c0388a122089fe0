#include "io/CheckpointFile.h"
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace cellphase
{
namespace
{
constexpr char magic[8] = {'C', 'P', 'H', 'C', 'K', 'P', 'T', '1'};
constexpr std::uint64_t fnv_offset = 14695981039346656037ull, fnv_prime = 1099511628211ull;

std::uint64_t fnv1a(const char* data, std::size_t n)
{
  std::uint64_t h = fnv_offset;
  for (std::size_t i = 0; i < n; ++i)
    h = (h ^ std::uint8_t(data[i])) * fnv_prime;
  return h;
}

void put_u64(std::string& out, std::uint64_t v) { out.append(reinterpret_cast<char*>(&v), 8); }
void put_bytes(std::string& out, const std::string& s)
{
  put_u64(out, s.size());
  out += s;
}

/// Sequential reader that reports where a short file ends.
struct Cursor
{
  const std::string& bytes;
  std::size_t pos = 0, end;
  std::uint64_t u64()
  {
    need(8);
    std::uint64_t v;
    std::memcpy(&v, bytes.data() + pos, 8);
    pos += 8;
    return v;
  }
  std::string chunk(std::size_t n)
  {
    need(n);
    std::string s = bytes.substr(pos, n);
    pos += n;
    return s;
  }
  void need(std::size_t n) const
  {
    if (n > end - pos)
      throw CheckpointError("corrupt: an entry runs past the end of the data");
  }
};
} // namespace

double CheckpointData::scalar(const std::string& name) const
{
  const auto& a = array(name);
  if (a.size() != 1)
    throw CheckpointError("entry '" + name + "' is not a single number");
  return a[0];
}

const std::vector<double>& CheckpointData::array(const std::string& name) const
{
  auto it = arrays.find(name);
  if (it == arrays.end())
    throw CheckpointError("entry '" + name + "' is missing");
  return it->second;
}

const std::string& CheckpointData::text(const std::string& name) const
{
  auto it = texts.find(name);
  if (it == texts.end())
    throw CheckpointError("entry '" + name + "' is missing");
  return it->second;
}

// Layout: magic | n_arrays | (name, count, doubles)* | n_texts | (name, text)* |
//         payload size | FNV-1a hash of everything before the size.
std::string encode(const CheckpointData& data)
{
  std::string out(magic, sizeof magic);
  put_u64(out, data.arrays.size());
  for (const auto& [name, values] : data.arrays)
  {
    put_bytes(out, name);
    put_u64(out, values.size());
    out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  }
  put_u64(out, data.texts.size());
  for (const auto& [name, text] : data.texts)
  {
    put_bytes(out, name);
    put_bytes(out, text);
  }
  const std::uint64_t size = out.size(), hash = fnv1a(out.data(), out.size());
  put_u64(out, size);
  put_u64(out, hash);
  return out;
}

CheckpointData decode(const std::string& bytes)
{
  if (bytes.size() < sizeof magic + 16 || std::memcmp(bytes.data(), magic, sizeof magic) != 0)
    throw CheckpointError(bytes.size() < sizeof magic ? "truncated: the file is almost empty"
                                                      : "not a cellphase checkpoint");
  std::uint64_t size, hash;
  std::memcpy(&size, bytes.data() + bytes.size() - 16, 8);
  std::memcpy(&hash, bytes.data() + bytes.size() - 8, 8);
  if (size != bytes.size() - 16)
    throw CheckpointError("truncated or damaged: its " + std::to_string(bytes.size())
                          + " bytes do not end with the size record of a complete checkpoint");
  if (fnv1a(bytes.data(), size) != hash)
    throw CheckpointError("corrupt: the content does not match its hash");

  Cursor c{bytes, sizeof magic, size};
  CheckpointData data;
  for (std::uint64_t n = c.u64(), i = 0; i < n; ++i)
  {
    std::string name = c.chunk(c.u64());
    const std::uint64_t count = c.u64();
    if (count > (c.end - c.pos) / sizeof(double))
      throw CheckpointError("corrupt: array '" + name + "' runs past the end of the data");
    std::vector<double> values(count);
    std::memcpy(values.data(), bytes.data() + c.pos, count * sizeof(double));
    c.pos += count * sizeof(double);
    data.arrays[name] = std::move(values);
  }
  for (std::uint64_t n = c.u64(), i = 0; i < n; ++i)
  {
    std::string name = c.chunk(c.u64());
    data.texts[name] = c.chunk(c.u64());
  }
  return data;
}

void write_file_atomically(const std::string& path, const std::string& bytes)
{
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0)
    throw std::runtime_error("cannot write checkpoint '" + tmp + "': " + std::strerror(errno));
  std::size_t done = 0;
  while (done < bytes.size())
  {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR)
      continue;
    if (n <= 0)
    {
      const std::string why = std::strerror(errno);
      ::close(fd);
      throw std::runtime_error("cannot write checkpoint '" + tmp + "': " + why);
    }
    done += std::size_t(n);
  }
  // The data must be on disk before the rename makes it the checkpoint of record.
  if (::fsync(fd) != 0 || ::close(fd) != 0)
    throw std::runtime_error("cannot write checkpoint '" + tmp + "': " + std::strerror(errno));
  std::filesystem::rename(tmp, path);
}

std::string read_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw CheckpointError("cannot be read: " + std::string(std::strerror(errno)));
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
} // namespace cellphase
