"""Facts from ROS 2 itself that tests check against."""

# ROS 2's own values: those the lab's brief quotes, and those rosidl wrote into ROS 2 Kilted's packages
# (share/<pkg>/msg/<Type>.json), read once; tf2_msgs/msg/TFMessage has no such file here.
ROS_REFERENCE_HASHES = {
    "builtin_interfaces/msg/Duration": "e8d009f659816f758b75334ee1a9ca5b5c0b859843261f14c7f937349599d93b",
    "builtin_interfaces/msg/Time": "b106235e25a4c5ed35098aa0a61a3ee9c9b18d197f398b0e4206cea9acf9c197",
    "example_interfaces/srv/AddTwoInts": "e118de6bf5eeb66a2491b5bda11202e7b68f198d6f67922cf30364858239c81a",
    "geometry_msgs/msg/Point": "6963084842a9b04494d6b2941d11444708d892da2f4b09843b9c43f42a7f6881",
    "geometry_msgs/msg/PointStamped": "4c0296af86e01e562e9e0405d138a01537247580076c58ea38d7923ac1045897",
    "geometry_msgs/msg/Pose": "d501954e9476cea2996984e812054b68026ae0bfae789d9a10b23daf35cc90fa",
    "geometry_msgs/msg/PoseStamped": "10f3786d7d40fd2b54367835614bff85d4ad3b5dab62bf8bca0cc232d73b4cd8",
    "geometry_msgs/msg/Quaternion": "8a765f66778c8ff7c8ab94afcc590a2ed5325a1d9a076ffff38fbce36f458684",
    "geometry_msgs/msg/Transform": "beb83fbe698636351461f6f35d1abb20010c43d55374d81bd041f1ba2581fddc",
    "geometry_msgs/msg/TransformStamped": "0a241f87d04668d94099cbb5ba11691d5ad32c2f29682e4eb5653424bd275206",
    "geometry_msgs/msg/Twist": "9c45bf16fe0983d80e3cfe750d6835843d265a9a6c46bd2e609fcddde6fb8d2a",
    "geometry_msgs/msg/TwistStamped": "5f0fcd4f81d5d06ad9b4c4c63e3ea51b82d6ae4d0558f1d475229b1121db6f64",
    "geometry_msgs/msg/Vector3": "cc12fe83e4c02719f1ce8070bfd14aecd40f75a96696a67a2a1f37f7dbb0765d",
    "geometry_msgs/msg/Vector3Stamped": "d4829622288cbb443886e7ea94ea5671a3b1be6bab4ad04224432a65f7d7887a",
    "keyboard_msgs/msg/Key": "14014a31d8ce72bf3dbb9d6b501ee35d5f50b653e785dea9ed750b7dc74f4a48",
    "rcl_interfaces/msg/Log": "e28ce254ca8abc06abf92773b74602cdbf116ed34fbaf294fb9f81da9f318eac",
    "sensor_msgs/msg/Imu": "7d9a00ff131080897a5ec7e26e315954b8eae3353c3f995c55faf71574000b5b",
    "service_msgs/msg/ServiceEventInfo": "41bcbbe07a75c9b52bc96bfd5c24d7f0fc0a08c0cb7921b3373c5732345a6f45",
    "std_msgs/msg/Bool": "feb91e995ff9ebd09c0cb3d2aed18b11077585839fb5db80193b62d74528f6c9",
    "std_msgs/msg/Byte": "41e1a3345f73fe93ede006da826a6ee274af23dd4653976ff249b0f44e3e798f",
    "std_msgs/msg/Char": "3ad2d04dd29ba19d04b16659afa3ccaedd691914b02a64e82e252f2fa6a586a9",
    "std_msgs/msg/ColorRGBA": "77a7a5b9ae477306097665106e0413ba74440245b1f3d0c6d6405fe5c7813fe8",
    "std_msgs/msg/Empty": "20b625256f32d5dbc0d04fee44f43c41e51c70d3502f84b4a08e7a9c26a96312",
    "std_msgs/msg/Float32": "7170d3d8f841f7be3172ce5f4f59f3a4d7f63b0447e8b33327601ad64d83d6e2",
    "std_msgs/msg/Float64": "705ba9c3d1a09df43737eb67095534de36fd426c0587779bda2bc51fe790182a",
    "std_msgs/msg/Header": "f49fb3ae2cf070f793645ff749683ac6b06203e41c891e17701b1cb597ce6a01",
    "std_msgs/msg/Int16": "1dcc3464e47c288a55f943a389d337cdb06804de3f5cd7a266b0de718eee17e5",
    "std_msgs/msg/Int32": "b6578ded3c58c626cfe8d1a6fb6e04f706f97e9f03d2727c9ff4e74b1cef0deb",
    "std_msgs/msg/Int64": "8cd1048c2f186b6bd9a92472dc1ce51723c0833a221e2b7aecfff111774f4b49",
    "std_msgs/msg/Int8": "26525065a403d972cb672f0777e333f0c799ad444ae5fcd79e43d1e73bd0f440",
    "std_msgs/msg/String": "df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18",
    "std_msgs/msg/UInt16": "08a406e4b022bc22e907f985d6a9e9dd1d4fbecae573549cf49350113e7757b1",
    "std_msgs/msg/UInt32": "a5c874829b752bc5fa190024b0ad76f578cc278271e855c7d02a818b3516fb4a",
    "std_msgs/msg/UInt64": "fbdc52018fc13755dce18024d1a671c856aa8b4aaf63adfb095b608f98e8c943",
    "std_msgs/msg/UInt8": "6138bd83d8c3569cb80a667db03cfc1629f529fee79d944c39c34e352e72f010",
    # action_msgs and unique_identifier_msgs as rosidl wrote them into ROS 2 Kilted's packages.
    "action_msgs/msg/GoalInfo": "6398fe763154554353930716b225947f93b672f0fb2e49fdd01bb7a7e37933e9",
    "action_msgs/msg/GoalStatus": "32f4cfd717735d17657e1178f24431c1ce996c878c515230f6c5b3476819dbb9",
    "action_msgs/msg/GoalStatusArray": "6c1684b00f177d37438febe6e709fc4e2b0d4248dca4854946f9ed8b30cda83e",
    "action_msgs/srv/CancelGoal": "573d8b0a534451d7bc2ac8c5ffde8ac14b8593b7001175d0cd6516dcbeb8689a",
    "unique_identifier_msgs/msg/UUID": "1b8e8aca958cbea28fe6ef60bf6c19b683c97a9ef60bb34752067d0f2f7ab437",
    # example_interfaces' Fibonacci action as rosidl hashes it (quoted alike by two independent
    # implementations checked against rosidl's output).
    "example_interfaces/action/Fibonacci": "9508051da1ea4658de144b09bd0690ff3de52104683d847aed764d2915906f51",
    "example_interfaces/action/Fibonacci_Goal": "226cb437e4355dcd3e914f930382a3b0cc1da81545bd319ed554e95a03255f51",
    "example_interfaces/action/Fibonacci_SendGoal": "d1a57fb2a4afe8c21e34fb10db206f16ce6729b28531141472df92277c55b557",
    "example_interfaces/action/Fibonacci_GetResult": "1b0de0d5d29dc955d92f546706568428632771db13ec84c15ec1c1a59f424a57",
    "example_interfaces/action/Fibonacci_FeedbackMessage": (
        "c1de71afd52e49a89c53d8262366884185bc0a02f78ce051c4e46b0a7fe59bb2"
    ),
    # The parameter services, as independent rmw_zenoh peers list them for ROS 2's parameter tools.
    "rcl_interfaces/srv/DescribeParameters": "845b484d71eb0673dae682f2e3ba3c4851a65a3dcfb97bddd82c5b57e91e4cff",
    "rcl_interfaces/srv/GetParameterTypes": "da199c878688b3e530bdfe3ca8f74cb9fa0c303101e980a9e8f260e25e1c80ca",
    "rcl_interfaces/srv/GetParameters": "bf9803d5c74cf989a5de3e0c2e99444599a627c7ff75f97b8c05b01003675cbc",
    "rcl_interfaces/srv/ListParameters": "3e6062bfbb27bfb8730d4cef2558221f51a11646d78e7bb30a1e83afac3aad9d",
    "rcl_interfaces/srv/SetParameters": "56eed9a67e169f9cb6c1f987bc88f868c14a8fc9f743a263bc734c154015d7e0",
    "rcl_interfaces/srv/SetParametersAtomically": "0e192ef259c07fc3c07a13191d27002222e65e00ccec653ca05e856f79285fcd",
    "std_srvs/srv/Empty": "5888399dedec5ccc85ea6451949fd2c9f97bfdf963f9a588821639fcd31b5d19",
    "std_srvs/srv/SetBool": "abe9e4bb6b41b40e6789712c00ec8871923e089af3f667a79992a428cff2da0a",
    "std_srvs/srv/Trigger": "eeff2cd6fa5ad9d27cdf4dec64818317839b62f212a91e6b5304b634b2062c5f",
}


def rihs(type_name: str) -> str:
    """``RIHS01_<hex>``, as rmw_zenoh's keys and tokens carry a type's hash, from ROS 2's own value."""
    return "RIHS01_" + ROS_REFERENCE_HASHES[type_name]
