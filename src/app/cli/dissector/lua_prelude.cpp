// The first fixed part of the generated plugin: what the configured exchanges are built with.

#include "app/cli/dissector/detail/lua_runtime.hpp"

namespace eip2mqtt::app::dissector::detail {

const std::string_view lua_prelude = R"lua(
local eip2mqtt = Proto("eip2mqtt", "eip2mqtt: Ethernet Global Data, as configured")

local fields = {}
local function field(f)
  fields[#fields + 1] = f
  return f
end

local hf = {
  pdu_type = field(ProtoField.uint8("eip2mqtt.pdu_type", "PDU type", base.HEX)),
  pdu_version = field(ProtoField.uint8("eip2mqtt.pdu_version", "PDU version")),
  request_id = field(ProtoField.uint16("eip2mqtt.request_id", "Request id")),
  producer_id = field(ProtoField.ipv4("eip2mqtt.producer_id", "Producer id")),
  exchange_id = field(ProtoField.uint32("eip2mqtt.exchange_id", "Exchange id")),
  timestamp = field(ProtoField.absolute_time("eip2mqtt.timestamp", "Timestamp", base.UTC)),
  status = field(ProtoField.uint32("eip2mqtt.status", "Status")),
  signature = field(ProtoField.string("eip2mqtt.signature", "Signature (major.minor)")),
  reserved = field(ProtoField.uint32("eip2mqtt.reserved", "Reserved", base.HEX)),
  exchange = field(ProtoField.string("eip2mqtt.exchange", "Exchange")),
  data = field(ProtoField.bytes("eip2mqtt.data", "Data")),
}

-- Expert entries are fields too: their names live under eip2mqtt.expert, a part no exchange
-- takes.
local function expert_entry(name, text, group, severity)
  return ProtoExpert.new("eip2mqtt.expert." .. name, text, group, severity)
end
local experts = {
  malformed = expert_entry("malformed", "Not a valid data datagram",
    expert.group.MALFORMED, expert.severity.ERROR),
  unknown_exchange = expert_entry("unknown_exchange", "Exchange nobody configured",
    expert.group.UNDECODED, expert.severity.WARN),
  signature_mismatch = expert_entry("signature_mismatch",
    "Signature does not match the configuration", expert.group.PROTOCOL, expert.severity.WARN),
  length_mismatch = expert_entry("length_mismatch", "Length does not match the configuration",
    expert.group.PROTOCOL, expert.severity.WARN),
  missed = expert_entry("missed", "Request ids missed",
    expert.group.SEQUENCE, expert.severity.WARN),
  duplicate = expert_entry("duplicate", "Duplicate request id",
    expert.group.SEQUENCE, expert.severity.WARN),
  out_of_order = expert_entry("out_of_order", "Request id steps back",
    expert.group.SEQUENCE, expert.severity.WARN),
  restart = expert_entry("restart", "Producer restarted",
    expert.group.SEQUENCE, expert.severity.NOTE),
  status = expert_entry("status", "Status not 0",
    expert.group.RESPONSE_CODE, expert.severity.WARN),
  clock_unsynced = expert_entry("clock_unsynced", "Producer clock unsynchronised",
    expert.group.PROTOCOL, expert.severity.WARN),
}
do
  local list = {}
  for _, entry in pairs(experts) do list[#list + 1] = entry end
  eip2mqtt.experts = list
end

local tag_types = {
  bit = { size = 1 },
  byte = { size = 1, make = ProtoField.uint8 },
  int = { size = 2, make = ProtoField.int16 },
  word = { size = 2, make = ProtoField.uint16 },
  dint = { size = 4, make = ProtoField.int32 },
  udint = { size = 4, make = ProtoField.uint32 },
  real = { size = 4, make = ProtoField.float },
  lint = { size = 8, make = ProtoField.int64 },
  lreal = { size = 8, make = ProtoField.double },
  string = { size = 1, make = ProtoField.string },
}

-- A scaled tag's raw value as a Lua number (lint through Int64, to the nearest double, as the
-- gateway scales it).
local raw_readers = {
  byte = "le_uint", int = "le_int", word = "le_uint", dint = "le_int", udint = "le_uint",
  real = "le_float", lreal = "le_float",
}
local function raw_number(range, type)
  if type == "lint" then return range:le_int64():tonumber() end
  return range[raw_readers[type]](range)
end

-- The engineering value of `raw` by the tag's scale (docs/configuration.md "Engineering
-- values"): gain and offset, or linear or square root between two ranges, exact at their ends.
local function engineering(s, raw)
  if s.kind == "gain" then return raw * s.gain + s.offset end
  local t = (raw - s.raw[1]) / (s.raw[2] - s.raw[1])
  if t < 0 then
    if s.clamp or s.kind == "sqrt" then t = 0 end
  elseif t > 1 and s.clamp then
    t = 1
  end
  if s.kind == "sqrt" then t = math.sqrt(t) end
  if t == 1 then return s.eu[2] end
  return s.eu[1] + t * (s.eu[2] - s.eu[1])
end

-- Configured exchanges by "producer id/exchange id"; the first of two with one key decodes it.
-- A scaled tag shows its raw field and, beside it, its engineering value (`<field>.eu`).
-- An array (`count`) shows each element as its own item, "[i]" before it; a string is one
-- field of `count` bytes.
local exchanges = {}
local function exchange(ex, define_tags)
  ex.tags = {}
  define_tags(function(abbr, label, type, offset, bit, scale, eu_label, count)
    count = count or 1
    local f
    if type == "bit" and count > 1 then
      f = ProtoField.bool(abbr, label)
    elseif type == "bit" then
      f = ProtoField.bool(abbr, label, 8, nil, 2 ^ bit)
    else
      f = tag_types[type].make(abbr, label)
    end
    local tag = { field = field(f), offset = offset, bit = bit, size = tag_types[type].size,
                  type = type, count = count }
    if type == "string" then
      tag.size = count
      tag.count = 1
    end
    if scale then
      tag.scale = scale
      tag.eu_field = field(ProtoField.double(abbr .. ".eu", eu_label))
    end
    ex.tags[#ex.tags + 1] = tag
  end)
  if exchanges[ex.key] == nil then exchanges[ex.key] = ex end
end
)lua";

}  // namespace eip2mqtt::app::dissector::detail
