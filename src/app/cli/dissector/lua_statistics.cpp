// The third fixed part of the generated plugin: per-exchange statistics, the figures `eip2mqtt
// sniff` prints, for `tshark -z eip2mqtt,stat` and Wireshark's Statistics menu.

#include "app/cli/dissector/detail/lua_runtime.hpp"

namespace eip2mqtt::app::dissector::detail {

const std::string_view lua_statistics = R"lua(
-- Every exchange seen, in order of first appearance. The jitter is RFC 3550's estimator over
-- the periods between datagrams, against the configured period (else the mean so far), as
-- sniff computes it (core::exchange::ArrivalStats).
local arrivals, arrival_order
local function reset_statistics()
  arrivals, arrival_order = {}, {}
end
reset_statistics()

local function arrival_of(key, ex)
  local a = arrivals[key]
  if a == nil then
    a = { label = ex and ex.name or key, expected = ex and ex.period_ms / 1000 or nil,
          count = 0, jitter = 0, missed = 0, duplicates = 0, out_of_order = 0 }
    arrivals[key] = a
    arrival_order[#arrival_order + 1] = a
  end
  return a
end

local function record_arrival(key, ex, at_s, found)
  local a = arrival_of(key, ex)
  if a.count == 0 then
    a.first = at_s
  else
    at_s = math.max(at_s, a.last)
    local period = at_s - a.last
    local reference = a.expected
    if reference == nil and a.count >= 2 then reference = (a.last - a.first) / (a.count - 1) end
    if reference ~= nil then a.jitter = a.jitter + (math.abs(period - reference) - a.jitter) / 16 end
    if a.min == nil or period < a.min then a.min = period end
    if a.max == nil or period > a.max then a.max = period end
  end
  a.last = at_s
  a.count = a.count + 1
  for _, f in ipairs(found) do
    if f[1] == experts.missed then a.missed = a.missed + f[3] end
    if f[1] == experts.duplicate then a.duplicates = a.duplicates + 1 end
    if f[1] == experts.out_of_order then a.out_of_order = a.out_of_order + 1 end
  end
end

local function ms(seconds)
  if seconds == nil then return "-" end
  return string.format("%.3f", seconds * 1000)
end

local function statistics_text()
  local width = 8
  for _, a in ipairs(arrival_order) do width = math.max(width, #a.label) end
  local row = "%-" .. width .. "s %9s %10s %10s %10s %10s %8s %10s %12s\n"
  local lines = { "eip2mqtt statistics per exchange (periods and jitter in ms)\n",
    string.format(row, "exchange", "datagrams", "period", "min", "max", "jitter", "missed",
      "duplicates", "out_of_order") }
  for _, a in ipairs(arrival_order) do
    local mean = a.count > 1 and (a.last - a.first) / (a.count - 1) or nil
    lines[#lines + 1] = string.format(row, a.label, a.count, ms(mean), ms(a.min), ms(a.max),
      a.count > 1 and ms(a.jitter) or "-", a.missed, a.duplicates, a.out_of_order)
  end
  return table.concat(lines)
end

register_stat_cmd_arg("eip2mqtt,stat", function()
  -- The dissector gathers the figures; the tap only prints them once the capture is read.
  -- No filter: a filter would make tshark build every frame's tree.
  local tap = Listener.new()
  function tap.draw()
    io.write(statistics_text())
  end
end)

if gui_enabled() then
  register_menu("eip2mqtt/Statistics per exchange", function()
    local window = TextWindow.new("eip2mqtt statistics")
    window:set(statistics_text())
  end, MENU_STAT_GENERIC)
end
)lua";

}  // namespace eip2mqtt::app::dissector::detail
