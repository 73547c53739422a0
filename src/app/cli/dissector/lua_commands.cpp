// The last fixed part of the generated plugin: the command protocol on UDP 7937
// (docs/protocol.md §9), every PDU with its fields, as protocol `eip2mqtt_cmd`.

#include "app/cli/dissector/detail/lua_runtime.hpp"

namespace eip2mqtt::app::dissector::detail {

const std::string_view lua_commands = R"lua(
local cmd = Proto("eip2mqtt_cmd", "eip2mqtt commands: the EGD command protocol")

local pdu_types = {
  [3] = "Retrieve Configuration request", [4] = "Retrieve Configuration response",
  [7] = "Summary request", [8] = "Summary response",
  [9] = "Capabilities request", [10] = "Capabilities response",
  [15] = "Statistics request", [16] = "Statistics response", [18] = "Command NAK",
  [32] = "Read request", [33] = "Read response", [34] = "Write request",
  [35] = "Write response", [36] = "Masked Write request", [37] = "Masked Write response",
}
local statuses = { [0] = "success", [1] = "unknown_exchange", [2] = "not_permitted",
  [3] = "out_of_range", [4] = "rejected", [5] = "signature_mismatch",
  [6] = "unsupported_address", [7] = "no_data", [8] = "failed", [9] = "prove_address" }
local nak_reasons = { [1] = "oversized", [2] = "wrong_version", [3] = "wrong_length",
  [4] = "unknown_type", [5] = "truncated", [6] = "malformed" }
local modes = { [1] = "produced", [2] = "consumed" }
local states = { [1] = "idle", [2] = "active" }
local destination_types = { [0] = "none", [1] = "unicast", [2] = "multicast", [3] = "broadcast" }

local function c(abbr) return "eip2mqtt_cmd." .. abbr end
local cf = {
  type = ProtoField.uint8(c("type"), "PDU type", base.DEC, pdu_types),
  flag = ProtoField.uint8(c("flag"), "Message flag"),
  request_id = ProtoField.uint16(c("request_id"), "Request id"),
  version = ProtoField.uint8(c("version"), "Protocol version"),
  status = ProtoField.uint8(c("status"), "Status", base.DEC, statuses),
  length = ProtoField.uint16(c("length"), "Message length"),
  producer_id = ProtoField.ipv4(c("producer_id"), "Producer id"),
  exchange_id = ProtoField.uint32(c("exchange_id"), "Exchange id"),
  period_ms = ProtoField.uint32(c("period_ms"), "Period (ms)"),
  destination_type = ProtoField.uint16(c("destination_type"), "Destination type", base.DEC,
    destination_types),
  destination = ProtoField.ipv4(c("destination"), "Destination"),
  state = ProtoField.uint16(c("state"), "State", base.DEC, states),
  exchange_length = ProtoField.uint16(c("exchange_length"), "Exchange length"),
  data_port = ProtoField.uint16(c("data_port"), "Data port"),
  signature = ProtoField.string(c("signature"), "Signature (major.minor)"),
  mode = ProtoField.uint16(c("mode"), "Mode", base.DEC, modes),
  index = ProtoField.uint8(c("index"), "First index"),
  total = ProtoField.uint16(c("total"), "Exchanges of the node"),
  count = ProtoField.uint16(c("count"), "Exchanges in this response"),
  entry = ProtoField.bytes(c("entry"), "Exchange"),
  entry_mode = ProtoField.uint8(c("entry.mode"), "Mode", base.DEC, modes),
  max_exchanges = ProtoField.uint32(c("max_exchanges"), "Most exchanges"),
  capabilities = ProtoField.uint32(c("capabilities"), "Capabilities", base.HEX),
  identification = ProtoField.string(c("identification"), "Identification"),
  configured_at = ProtoField.absolute_time(c("stats.configured_at"), "Configured at", base.UTC),
  due_ms = ProtoField.uint32(c("stats.due_ms"), "Next due (ms)"),
  stats_state = ProtoField.uint32(c("stats.state"), "State", base.DEC, states),
  stats_length = ProtoField.uint32(c("stats.length"), "Exchange length"),
  messages = ProtoField.uint32(c("stats.messages"), "Messages"),
  missed = ProtoField.uint32(c("stats.missed"), "Missed"),
  refresh_errors = ProtoField.uint32(c("stats.refresh_errors"), "Refresh errors"),
  address_type = ProtoField.uint8(c("address_type"), "Address type"),
  cells = ProtoField.uint8(c("cells"), "Cells"),
  data_time = ProtoField.absolute_time(c("data_time"), "Time of the data", base.UTC),
  cell = ProtoField.bytes(c("cell"), "Cell"),
  cell_offset = ProtoField.uint16(c("cell.offset"), "Offset"),
  cell_length = ProtoField.uint16(c("cell.length"), "Length"),
  cell_data = ProtoField.bytes(c("cell.data"), "Data"),
  cell_mask = ProtoField.bytes(c("cell.mask"), "Mask"),
  nak_reason = ProtoField.uint16(c("nak.reason"), "Reason", base.DEC, nak_reasons),
  nak_request = ProtoField.bytes(c("nak.request"), "Start of the request"),
  nak_error = ProtoField.string(c("nak.error"), "Error"),
  token = ProtoField.uint32(c("token"), "Address token", base.HEX),
}
do
  local list = {}
  for _, f in pairs(cf) do list[#list + 1] = f end
  cmd.fields = list
end
local cmd_truncated = ProtoExpert.new("eip2mqtt_cmd.truncated", "PDU shorter than its type's fields",
  expert.group.MALFORMED, expert.severity.ERROR)
cmd.experts = { cmd_truncated }

-- The fewest bytes each PDU type's fields take.
local sizes = { [3] = 16, [4] = 76, [7] = 12, [8] = 17, [9] = 8, [10] = 28, [15] = 16,
  [16] = 48, [18] = 36, [32] = 32, [33] = 32, [34] = 32, [35] = 32, [36] = 32, [37] = 32 }

local function add_ids(t, buf)
  t:add(cf.producer_id, buf(8, 4))
  t:add_le(cf.exchange_id, buf(12, 4))
end

local function add_signature(t, range)
  t:add(cf.signature, range, string.format("%d.%d", range(1, 1):uint(), range(0, 1):uint()))
end

-- A string of up to 80 characters, ending at its NUL if it has one.
local function add_text(t, field, range)
  local text = range:string()
  local nul = text:find("\0", 1, true)
  if nul then text = text:sub(1, nul - 1) end
  t:add(field, range, text)
end

local bodies = {}
bodies[3] = add_ids
bodies[15] = add_ids
bodies[4] = function(t, buf)
  add_ids(t, buf)
  t:add_le(cf.period_ms, buf(16, 4))
  t:add_le(cf.destination_type, buf(22, 2))
  t:add(cf.destination, buf(24, 4))
  t:add_le(cf.state, buf(56, 2))
  t:add_le(cf.exchange_length, buf(58, 2))
  t:add_le(cf.data_port, buf(64, 2))
  add_signature(t, buf(68, 2))
  t:add_le(cf.mode, buf(70, 2))
end
bodies[7] = function(t, buf) t:add(cf.index, buf(8, 1)) end
bodies[8] = function(t, buf)
  t:add(cf.index, buf(8, 1))
  t:add(cf.producer_id, buf(9, 4))
  t:add_le(cf.total, buf(13, 2))
  t:add_le(cf.count, buf(15, 2))
  local at = 17
  for _ = 1, buf(15, 2):le_uint() do
    if buf:len() < at + 16 then return false end
    local entry = t:add(cf.entry, buf(at, 16))
    entry:add(cf.producer_id, buf(at, 4))
    entry:add_le(cf.exchange_id, buf(at + 4, 4))
    entry:add(cf.entry_mode, buf(at + 8, 1))
    entry:add_le(cf.state, buf(at + 10, 2))
    entry:add_le(cf.period_ms, buf(at + 12, 4))
    at = at + 16
  end
end
bodies[9] = function(t, buf)
  if buf:len() >= 12 then t:add(cf.producer_id, buf(8, 4)) end
end
bodies[10] = function(t, buf)
  t:add(cf.producer_id, buf(8, 4))
  t:add_le(cf.max_exchanges, buf(16, 4))
  t:add_le(cf.capabilities, buf(20, 4))
  if buf:len() > 28 then add_text(t, cf.identification, buf(28, math.min(buf:len() - 28, 80))) end
end
bodies[16] = function(t, buf)
  add_ids(t, buf)
  t:add(cf.configured_at, buf(16, 4), NSTime.new(buf(16, 4):le_uint(), 0))
  t:add_le(cf.due_ms, buf(20, 4))
  t:add_le(cf.stats_state, buf(24, 4))
  t:add_le(cf.stats_length, buf(28, 4))
  t:add_le(cf.messages, buf(32, 4))
  t:add_le(cf.missed, buf(36, 4))
  t:add_le(cf.refresh_errors, buf(40, 4))
end
bodies[18] = function(t, buf)
  add_ids(t, buf)
  t:add_le(cf.nak_reason, buf(16, 2))
  t:add(cf.nak_request, buf(20, 16))
  if buf:len() > 36 then add_text(t, cf.nak_error, buf(36, math.min(buf:len() - 36, 80))) end
end

-- How many padded copies of its bytes a cell of each type carries: data, or data and mask.
local cell_copies = { [32] = 0, [33] = 1, [34] = 1, [35] = 0, [36] = 2, [37] = 0 }

local function add_cells(t, buf, type)
  local at = 32
  for _ = 1, buf(11, 1):uint() do
    if buf:len() < at + 4 then return false end
    local length = buf(at + 2, 2):le_uint()
    local padded = math.floor((length + 3) / 4) * 4
    local size = 4 + padded * cell_copies[type]
    if buf:len() < at + size then return false end
    local cell = t:add(cf.cell, buf(at, size))
    cell:add_le(cf.cell_offset, buf(at, 2))
    cell:add_le(cf.cell_length, buf(at + 2, 2))
    if cell_copies[type] >= 1 and length > 0 then cell:add(cf.cell_data, buf(at + 4, length)) end
    if cell_copies[type] == 2 and length > 0 then
      cell:add(cf.cell_mask, buf(at + 4 + padded, length))
    end
    at = at + size
  end
end

for type = 32, 37 do
  bodies[type] = function(t, buf)
    add_signature(t, buf(8, 2))
    t:add(cf.address_type, buf(10, 1))
    t:add(cf.cells, buf(11, 1))
    t:add(cf.producer_id, buf(12, 4))
    t:add_le(cf.exchange_id, buf(16, 4))
    t:add(cf.data_time, buf(20, 8), NSTime.new(buf(20, 4):le_uint(), buf(24, 4):le_uint()))
    return add_cells(t, buf, type)
  end
end

function cmd.dissector(buf, pinfo, tree)
  local length = buf:len()
  if length < 8 then return 0 end
  pinfo.cols.protocol = "eip2mqtt_cmd"
  local root = tree:add(cmd, buf())
  local type = buf(0, 1):uint()
  root:add(cf.type, buf(0, 1))
  root:add(cf.flag, buf(1, 1))
  root:add_le(cf.request_id, buf(2, 2))
  root:add(cf.version, buf(4, 1))
  root:add(cf.status, buf(5, 1))
  root:add_le(cf.length, buf(6, 2))
  pinfo.cols.info = string.format("%s, request id %d", pdu_types[type] or
    string.format("PDU type %d", type), buf(2, 2):le_uint())
  -- docs/protocol.md 9.7: a challenge (status 9) is the header and the token, no body.
  if buf(5, 1):uint() == 9 and length <= 12 then
    if length == 12 then root:add_le(cf.token, buf(8, 4)) end
    pinfo.cols.info = string.format("%s, request id %d, challenge", pdu_types[type] or
      string.format("PDU type %d", type), buf(2, 2):le_uint())
    return length
  end
  local body = bodies[type]
  if body == nil then return length end
  if length < sizes[type] or body(root, buf) == false then
    root:add_proto_expert_info(cmd_truncated)
  end
  return length
end

DissectorTable.get("udp.port"):add(settings.command_port, cmd)
)lua";

}  // namespace eip2mqtt::app::dissector::detail
