#include "tools/fault_injector/fault_model.hpp"

#include <charconv>
#include <cstdio>

namespace eip2mqtt::fault_injector {
namespace {

constexpr std::array<std::string_view, 9> field_names{
    "type", "version", "rid", "producer", "exchange", "time", "status", "signature", "reserved",
};

constexpr std::array<std::string_view, fault_count> fault_names{
    "loss",      "corrupt_field", "corrupt_byte", "corrupt_bit", "truncate",
    "duplicate", "delay",         "jitter",       "reorder",
};

struct FieldSpan {
    std::size_t offset;
    std::size_t size;
};

// docs/protocol.md §2: where each header field lies.
FieldSpan span_of(HeaderField field) {
    switch (field) {
        case HeaderField::type:
            return {0, 1};
        case HeaderField::version:
            return {1, 1};
        case HeaderField::rid:
            return {2, 2};
        case HeaderField::producer:
            return {4, 4};
        case HeaderField::exchange:
            return {8, 4};
        case HeaderField::time:
            return {12, 4};
        case HeaderField::status:
            return {20, 4};
        case HeaderField::signature:
            return {24, 4};
        case HeaderField::reserved:
            return {28, 4};
    }
    return {0, 1};
}

std::optional<double> parse_probability(std::string_view text) {
    double p = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), p);
    if (ec != std::errc{} || end != text.data() + text.size() || !(p >= 0 && p <= 1)) {
        return std::nullopt;
    }
    return p;
}

std::optional<std::uint64_t> parse_unsigned(std::string_view text) {
    std::uint64_t n = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
    if (ec != std::errc{} || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return n;
}

// Splits "P:REST" into P and REST (REST empty when there is no colon).
std::pair<std::string_view, std::optional<std::string_view>> split_colon(std::string_view value) {
    const auto colon = value.find(':');
    if (colon == std::string_view::npos) return {value, std::nullopt};
    return {value.substr(0, colon), value.substr(colon + 1)};
}

core::Failure<std::string> bad(std::string_view name, std::string_view expected,
                               std::string_view value) {
    return core::fail("--" + std::string(name) + ": expected " + std::string(expected) + ", got '" +
                      std::string(value) + "'");
}

std::uint64_t read_field(const std::vector<std::byte>& bytes, FieldSpan span) {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < span.size; ++i) {
        v |= std::uint64_t{std::to_integer<std::uint8_t>(bytes[span.offset + i])} << (8 * i);
    }
    return v;
}

void write_field(std::vector<std::byte>& bytes, FieldSpan span, std::uint64_t v) {
    for (std::size_t i = 0; i < span.size; ++i) {
        bytes[span.offset + i] = static_cast<std::byte>(v >> (8 * i) & 0xFF);
    }
}

}  // namespace

std::optional<HeaderField> parse_header_field(std::string_view name) {
    for (std::size_t i = 0; i < field_names.size(); ++i) {
        if (field_names[i] == name) return static_cast<HeaderField>(i);
    }
    return std::nullopt;
}

std::string_view to_string(HeaderField field) {
    return field_names[static_cast<std::size_t>(field)];
}

std::string_view to_string(Fault fault) { return fault_names[static_cast<std::size_t>(fault)]; }

double FaultConfig::probability(Fault fault) const {
    switch (fault) {
        case Fault::loss:
            return loss;
        case Fault::corrupt_field:
            return corrupt_field;
        case Fault::corrupt_byte:
            return corrupt_byte;
        case Fault::corrupt_bit:
            return corrupt_bit;
        case Fault::truncate:
            return truncate;
        case Fault::duplicate:
            return duplicate;
        case Fault::delay:
            return delay.count() > 0 ? 1.0 : 0.0;
        case Fault::jitter:
            return jitter;
        case Fault::reorder:
            return reorder;
    }
    return 0;
}

core::Result<bool, std::string> apply_option(FaultConfig& config, std::string_view name,
                                             std::string_view value) {
    const auto [head, tail] = split_colon(value);
    if (name == "seed") {
        const auto n = parse_unsigned(value);
        if (!n) return bad(name, "an unsigned integer", value);
        config.seed = *n;
    } else if (name == "loss" || name == "duplicate" || name == "reorder") {
        const auto p = parse_probability(value);
        if (!p) return bad(name, "a probability 0..1", value);
        (name == "loss"        ? config.loss
         : name == "duplicate" ? config.duplicate
                               : config.reorder) = *p;
    } else if (name == "loss-burst") {
        const auto n = parse_unsigned(value);
        if (!n || *n == 0 || *n > 1000000) return bad(name, "a count 1..1000000", value);
        config.loss_burst = static_cast<unsigned>(*n);
    } else if (name == "delay") {
        const auto ms = parse_unsigned(value);
        if (!ms || *ms > 3600000) return bad(name, "milliseconds 0..3600000", value);
        config.delay = std::chrono::milliseconds(*ms);
    } else if (name == "jitter") {
        const auto p = parse_probability(head);
        const auto ms = tail ? parse_unsigned(*tail) : std::nullopt;
        if (!p || !ms || *ms > 3600000) return bad(name, "P:MS", value);
        config.jitter = *p;
        config.jitter_delay = std::chrono::milliseconds(*ms);
    } else if (name == "truncate" || name == "corrupt-byte" || name == "corrupt-bit") {
        const auto p = parse_probability(head);
        const auto n = tail ? parse_unsigned(*tail) : std::nullopt;
        if (!p || (tail && !n))
            return bad(name, name == "truncate" ? "P[:LENGTH]" : "P[:OFFSET]", value);
        const std::optional<std::size_t> where =
            n ? std::optional<std::size_t>(static_cast<std::size_t>(*n)) : std::nullopt;
        if (name == "truncate") {
            config.truncate = *p;
            config.truncate_length = where;
        } else if (name == "corrupt-byte") {
            config.corrupt_byte = *p;
            config.corrupt_byte_offset = where;
        } else {
            config.corrupt_bit = *p;
            config.corrupt_bit_offset = where;
        }
    } else if (name == "corrupt-field") {
        const auto p = parse_probability(head);
        const auto field = tail ? parse_header_field(*tail) : std::nullopt;
        if (!p || !field) {
            return bad(name,
                       "P:NAME with NAME one of type, version, rid, producer, exchange, time, "
                       "status, signature, reserved",
                       value);
        }
        config.corrupt_field = *p;
        config.field = *field;
    } else {
        return core::fail("unknown option --" + std::string(name));
    }
    return true;
}

std::uint64_t Rng::next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

double Rng::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

std::uint64_t Rng::below(std::uint64_t bound) { return next() % bound; }

FaultModel::FaultModel(const FaultConfig& config) : config_(config) {
    // One stream per fault, seeded apart, so that the decisions of one fault do not depend on
    // which other faults are enabled.
    rngs_.reserve(fault_count);
    Rng seeder(config.seed);
    for (std::size_t i = 0; i < fault_count; ++i) rngs_.emplace_back(seeder.next());
}

bool FaultModel::corrupt_field(std::vector<std::byte>& bytes) {
    const auto span = span_of(config_.field);
    if (bytes.size() < span.offset + span.size) return false;
    const std::uint64_t old = read_field(bytes, span);
    const std::uint64_t modulus = std::uint64_t{1} << (8 * span.size);
    // A different value: old + a non-zero step, modulo the field's range.
    const std::uint64_t step = 1 + rng(Fault::corrupt_field).below(modulus - 1);
    write_field(bytes, span, (old + step) % modulus);
    return true;
}

bool FaultModel::corrupt_byte(std::vector<std::byte>& bytes) {
    if (bytes.empty()) return false;
    auto& r = rng(Fault::corrupt_byte);
    const auto at = config_.corrupt_byte_offset && *config_.corrupt_byte_offset < bytes.size()
                        ? *config_.corrupt_byte_offset
                        : r.below(bytes.size());
    bytes[at] ^= static_cast<std::byte>(1 + r.below(255));
    return true;
}

bool FaultModel::corrupt_bit(std::vector<std::byte>& bytes) {
    if (bytes.empty()) return false;
    const auto bits = bytes.size() * 8;
    const auto at = config_.corrupt_bit_offset && *config_.corrupt_bit_offset < bits
                        ? *config_.corrupt_bit_offset
                        : rng(Fault::corrupt_bit).below(bits);
    bytes[at / 8] ^= static_cast<std::byte>(1u << (at % 8));
    return true;
}

bool FaultModel::truncate(std::vector<std::byte>& bytes) {
    if (bytes.empty()) return false;
    const auto length = config_.truncate_length && *config_.truncate_length < bytes.size()
                            ? *config_.truncate_length
                            : rng(Fault::truncate).below(bytes.size());
    bytes.resize(length);
    return true;
}

std::vector<Emission> FaultModel::on_datagram(std::vector<std::byte> datagram) {
    ++counters_.in;
    // Every fault draws once per datagram, whatever happens to it, so that each stream stays in
    // step with the datagram count.
    const auto draw = [&](Fault fault) { return rng(fault).chance(config_.probability(fault)); };
    const bool lose = draw(Fault::loss);
    const bool field = draw(Fault::corrupt_field);
    const bool byte = draw(Fault::corrupt_byte);
    const bool bit = draw(Fault::corrupt_bit);
    const bool cut = draw(Fault::truncate);
    const bool twice = draw(Fault::duplicate);
    const bool jitter = draw(Fault::jitter);
    const bool hold = draw(Fault::reorder);

    if (burst_left_ > 0 || lose) {
        if (burst_left_ > 0) {
            --burst_left_;
        } else {
            burst_left_ = config_.loss_burst - 1;
        }
        count(Fault::loss);
        return {};
    }
    if (field && corrupt_field(datagram)) count(Fault::corrupt_field);
    if (byte && corrupt_byte(datagram)) count(Fault::corrupt_byte);
    if (bit && corrupt_bit(datagram)) count(Fault::corrupt_bit);
    if (cut && truncate(datagram)) count(Fault::truncate);
    auto delay = config_.delay;
    if (delay.count() > 0) count(Fault::delay);
    if (jitter) {
        delay += config_.jitter_delay;
        count(Fault::jitter);
    }
    std::vector<Emission> out;
    if (twice) {
        out.push_back({datagram, delay});
        count(Fault::duplicate);
    }
    out.push_back({std::move(datagram), delay});

    if (!held_.empty()) {
        // The held datagram goes right after this one, so it arrives late.
        for (auto& e : held_) {
            e.delay = delay;
            out.push_back(std::move(e));
        }
        held_.clear();
        count(Fault::reorder);
    } else if (hold) {
        held_ = std::move(out);
        return {};
    }
    counters_.out += out.size();
    return out;
}

std::vector<Emission> FaultModel::flush() {
    auto out = std::move(held_);
    held_.clear();
    counters_.out += out.size();
    return out;
}

std::string format_report(const FaultModel& model, double seconds) {
    const auto& c = model.counters();
    std::string text;
    char line[160];
    std::snprintf(line, sizeof line,
                  "fault injector report: seed %llu, %.3f s\ndatagrams in: %llu, out: %llu\n",
                  static_cast<unsigned long long>(model.config().seed), seconds,
                  static_cast<unsigned long long>(c.in), static_cast<unsigned long long>(c.out));
    text += line;
    std::snprintf(line, sizeof line, "%-14s %11s %9s %9s\n", "fault", "probability", "affected",
                  "rate");
    text += line;
    for (std::size_t i = 0; i < fault_count; ++i) {
        const auto fault = static_cast<Fault>(i);
        const double rate = c.in == 0 ? 0.0 : static_cast<double>(c.of(fault)) / c.in;
        std::snprintf(line, sizeof line, "%-14s %11.4f %9llu %9.4f\n",
                      std::string(to_string(fault)).c_str(), model.config().probability(fault),
                      static_cast<unsigned long long>(c.of(fault)), rate);
        text += line;
    }
    return text;
}

std::string format_report_json(const FaultModel& model, double seconds) {
    const auto& c = model.counters();
    char buffer[200];
    std::snprintf(buffer, sizeof buffer, R"({"seed":%llu,"seconds":%.3f,"in":%llu,"out":%llu,)",
                  static_cast<unsigned long long>(model.config().seed), seconds,
                  static_cast<unsigned long long>(c.in), static_cast<unsigned long long>(c.out));
    std::string json = buffer;
    json += R"("faults":{)";
    for (std::size_t i = 0; i < fault_count; ++i) {
        const auto fault = static_cast<Fault>(i);
        std::snprintf(buffer, sizeof buffer, R"(%s"%s":{"probability":%.6g,"affected":%llu})",
                      i == 0 ? "" : ",", std::string(to_string(fault)).c_str(),
                      model.config().probability(fault),
                      static_cast<unsigned long long>(c.of(fault)));
        json += buffer;
    }
    json += "}}\n";
    return json;
}

}  // namespace eip2mqtt::fault_injector
