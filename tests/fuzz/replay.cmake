# Replays each fuzz target's seed corpus as a ctest in the normal build (gcc, no libFuzzer):
# replay_main.cpp feeds every file of tests/fuzz/corpus/<target>/ to LLVMFuzzerTestOneInput.
# Under EIP2MQTT_SANITIZE the replay runs with ASan + UBSan like every other test.
# Included from tests/CMakeLists.txt.

set(EIP2MQTT_FUZZ_DIR ${CMAKE_CURRENT_LIST_DIR})

function(eip2mqtt_fuzz_replay name)
  add_executable(fuzz_replay_${name}
    ${EIP2MQTT_FUZZ_DIR}/${name}_fuzz.cpp ${EIP2MQTT_FUZZ_DIR}/replay_main.cpp)
  target_link_libraries(fuzz_replay_${name} PRIVATE ${ARGN})
  add_test(NAME fuzz_replay_${name}
    COMMAND fuzz_replay_${name} ${EIP2MQTT_FUZZ_DIR}/corpus/${name})
  set_tests_properties(fuzz_replay_${name} PROPERTIES LABELS fuzz TIMEOUT 120)
endfunction()

eip2mqtt_fuzz_replay(decode_datagram eip2mqtt_core)
eip2mqtt_fuzz_replay(load_config eip2mqtt_adapters)
eip2mqtt_fuzz_replay(point_list eip2mqtt_core)
eip2mqtt_fuzz_replay(write_payload eip2mqtt_app)
eip2mqtt_fuzz_replay(write_router eip2mqtt_app nlohmann_json::nlohmann_json)
eip2mqtt_fuzz_replay(sparkplug_command eip2mqtt_adapters)
eip2mqtt_fuzz_replay(sparkplug_node eip2mqtt_app)
eip2mqtt_fuzz_replay(journal_samples eip2mqtt_adapters)
eip2mqtt_fuzz_replay(capture_frame eip2mqtt_adapters)
eip2mqtt_fuzz_replay(command_pdu eip2mqtt_core)
eip2mqtt_fuzz_replay(engineering_value eip2mqtt_core)
eip2mqtt_fuzz_replay(text_value eip2mqtt_core)
eip2mqtt_fuzz_replay(topic_template eip2mqtt_core)
