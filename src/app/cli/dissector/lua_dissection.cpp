// The second fixed part of the generated plugin: the gateway's consumer rules (docs/protocol.md
// §4) as expert info, and the dissector of the data port.

#include "app/cli/dissector/detail/lua_runtime.hpp"

namespace eip2mqtt::app::dissector::detail {

const std::string_view lua_dissection = R"lua(
-- What each exchange's last accepted datagram was (rule 6), and what was found in each frame:
-- judged once, on the first pass, in capture order, as the gateway judges them on arrival.
local sequences, findings
local function reset()
  sequences, findings = {}, {}
  reset_statistics()
end
reset()
eip2mqtt.init = reset

-- `count`: how many request ids a gap missed.
local function note(found, entry, text, count)
  found[#found + 1] = { entry, text, count }
end

-- Rule 4: "mismatch", "newer" (a compatible extension), or "ok".
local function signature_verdict(ex, h)
  if ex.signature == nil or h.signature == 0 then return "ok" end
  local major, minor = ex.signature[1], ex.signature[2]
  if h.sig_major ~= major or h.sig_minor < minor then return "mismatch" end
  if h.sig_minor > minor then return "newer" end
  return "ok"
end

local function stamped_later(h, last)
  if h.time_s == 0 or last.time_s == 0 then return false end
  return h.time_s > last.time_s or (h.time_s == last.time_s and h.time_ns > last.time_ns)
end

-- Rule 6, restarts included: true when the datagram is a new sample.
local function judge_sequence(st, h, found)
  if st.request_id == nil then return true end
  local d = (h.request_id - st.request_id) % 65536
  if d == 0 then
    note(found, experts.duplicate, string.format("Duplicate request id %d", h.request_id))
    return false
  end
  if d >= 32768 then
    if stamped_later(h, st) then
      note(found, experts.restart, string.format(
        "Producer restarted: request id %d after %d, with a later timestamp",
        h.request_id, st.request_id))
      return true
    end
    note(found, experts.out_of_order, string.format(
      "Request id %d steps back from %d", h.request_id, st.request_id))
    return false
  end
  if d > 1 then
    note(found, experts.missed, string.format(
      "%d request ids missed between %d and %d", d - 1, st.request_id, h.request_id), d - 1)
  end
  return true
end

local function judge_clock(ex, h, at_ms, found)
  if h.time_s == 0 then return end
  local tolerance = ex and ex.clock_tolerance_ms or settings.clock_tolerance_ms
  local offset = h.time_s * 1000 + math.floor(h.time_ns / 1000000) - at_ms
  if math.abs(offset) > tolerance then
    note(found, experts.clock_unsynced, string.format(
      "Producer clock %d ms %s the capture's, beyond clock_tolerance_ms %d",
      math.abs(offset), offset > 0 and "ahead of" or "behind", tolerance))
  end
end

-- Rules 4 and 5; false when the datagram is refused.
local function judge_configured(ex, h, data_length, found)
  local verdict = signature_verdict(ex, h)
  if verdict == "mismatch" then
    note(found, experts.signature_mismatch, string.format(
      "Signature %d.%d, configured %d.%d", h.sig_major, h.sig_minor,
      ex.signature[1], ex.signature[2]))
    return false
  end
  if data_length ~= ex.length and not (verdict == "newer" and data_length > ex.length) then
    note(found, experts.length_mismatch, string.format(
      "%d data bytes, configured %d", data_length, ex.length))
    return false
  end
  return true
end

local function judge(ex, key, h, data_length, at_ms)
  local found = {}
  if h.status ~= 0 then
    note(found, experts.status, string.format("Status %d", h.status))
  end
  local st = sequences[key]
  if st == nil then
    st = {}
    sequences[key] = st
  end
  if ex == nil then
    note(found, experts.unknown_exchange, string.format(
      "No configured exchange has producer id %s and exchange id %d",
      h.producer_id, h.exchange_id))
  elseif not judge_configured(ex, h, data_length, found) then
    st.request_id = nil
    return found
  elseif ex.timeout_ms > 0 and st.at_ms ~= nil and at_ms - st.at_ms > ex.timeout_ms then
    st.request_id = nil
  end
  if st.signature ~= h.signature then st.request_id = nil end
  if judge_sequence(st, h, found) then
    st.request_id, st.time_s, st.time_ns = h.request_id, h.time_s, h.time_ns
    st.at_ms, st.signature = at_ms, h.signature
    judge_clock(ex, h, at_ms, found)
  end
  return found
end

local function read_header(buf)
  local h = {
    request_id = buf(2, 2):le_uint(),
    producer_id = string.format("%d.%d.%d.%d",
      buf(4, 1):uint(), buf(5, 1):uint(), buf(6, 1):uint(), buf(7, 1):uint()),
    exchange_id = buf(8, 4):le_uint(),
    time_s = buf(12, 4):le_uint(),
    time_ns = buf(16, 4):le_uint(),
    status = buf(20, 4):le_uint(),
    sig_minor = buf(24, 1):uint(),
    sig_major = buf(25, 1):uint(),
  }
  h.signature = h.sig_major * 256 + h.sig_minor
  return h
end

local function add_header(root, buf, h)
  root:add(hf.pdu_type, buf(0, 1))
  root:add(hf.pdu_version, buf(1, 1))
  root:add_le(hf.request_id, buf(2, 2))
  root:add(hf.producer_id, buf(4, 4))
  root:add_le(hf.exchange_id, buf(8, 4))
  root:add(hf.timestamp, buf(12, 8), NSTime.new(h.time_s, h.time_ns))
  root:add_le(hf.status, buf(20, 4))
  root:add(hf.signature, buf(24, 2), string.format("%d.%d", h.sig_major, h.sig_minor))
  root:add_le(hf.reserved, buf(28, 4))
end

-- Element i of a tag: its byte range and, for a bit, its value.
local function element(buf, tag, i)
  if tag.type ~= "bit" or tag.count == 1 then
    return buf(32 + tag.offset + i * tag.size, tag.size), nil
  end
  local bit = tag.bit + i
  local range = buf(32 + tag.offset + math.floor(bit / 8), 1)
  return range, bit32.band(range:uint(), 2 ^ (bit % 8)) ~= 0
end

-- Where element i of a tag ends, in the data.
local function element_end(tag, i)
  if tag.type == "bit" and tag.count > 1 then return tag.offset + math.floor((tag.bit + i) / 8) + 1 end
  return tag.offset + (i + 1) * tag.size
end

-- A string's Latin-1 bytes without the NULs and spaces that pad its field.
local function text(range)
  return (range:string(ENC_ISO_8859_1):gsub("[%z ]+$", ""))
end

-- Every tag the data holds; a tag (an element) past the end of a short datagram is left out.
local function add_tags(root, buf, ex, data_length)
  local tree = root:add(hf.exchange, buf(32), ex.name)
  for _, tag in ipairs(ex.tags) do
    for i = 0, tag.count - 1 do
      if element_end(tag, i) > data_length then break end
      local range, bit = element(buf, tag, i)
      local item
      if bit ~= nil then
        item = tree:add(tag.field, range, bit)
      elseif tag.type == "string" then
        item = tree:add(tag.field, range, text(range))
      else
        item = tree:add_le(tag.field, range)
      end
      if tag.count > 1 then item:prepend_text("[" .. i .. "] ") end
      if tag.scale then
        local eu = tree:add(tag.eu_field, range, engineering(tag.scale, raw_number(range, tag.type)))
        if tag.count > 1 then eu:prepend_text("[" .. i .. "] ") end
      end
    end
  end
end

local function malformed(root, pinfo, text)
  root:add_proto_expert_info(experts.malformed, text)
  pinfo.cols.info = text
end

function eip2mqtt.dissector(buf, pinfo, tree)
  local length = buf:len()
  pinfo.cols.protocol = "eip2mqtt"
  local root = tree:add(eip2mqtt, buf())
  if length < 32 or buf(0, 1):uint() ~= 0x0D or buf(1, 1):uint() ~= 0x01 then
    malformed(root, pinfo, "Not a data datagram: too short, or not PDU type 0x0D version 1")
    return length
  end
  local h = read_header(buf)
  add_header(root, buf, h)
  local data_length = length - 32
  if data_length == 0 or data_length > 1400 then
    malformed(root, pinfo, string.format("%d data bytes: 1 to 1400 expected", data_length))
    return length
  end
  local key = h.producer_id .. "/" .. string.format("%d", h.exchange_id)
  local ex = exchanges[key]
  if not pinfo.visited then
    findings[pinfo.number] = judge(ex, key, h, data_length, math.floor(pinfo.abs_ts * 1000))
    -- Time since the first frame: small, so exact to the nanosecond in a double.
    record_arrival(key, ex, pinfo.rel_ts, findings[pinfo.number])
  end
  if ex then
    add_tags(root, buf, ex, data_length)
  else
    root:add(hf.data, buf(32))
  end
  for _, found in ipairs(findings[pinfo.number] or {}) do
    root:add_proto_expert_info(found[1], found[2])
  end
  pinfo.cols.info = string.format("%s request %d", ex and ex.name or key, h.request_id)
  return length
end

eip2mqtt.fields = fields
DissectorTable.get("udp.port"):add(settings.data_port, eip2mqtt)
)lua";

}  // namespace eip2mqtt::app::dissector::detail
