<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="tr">
  <context>
    <name>cnc</name>
    <message>
      <location filename="../../app/widgets/status_header.py" line="176" />
      <source> (+{0} more)</source>
      <translation> (+{0} tane daha)</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="174" />
      <source> (first {0:.0f} s shown)</source>
      <translation> (ilk {0:.0f} s gösteriliyor)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="472" />
      <source>/ lines skipped</source>
      <translation>/ satırları atlanıyor</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="177" />
      <source>ALARM: {0}: {1}</source>
      <translation>ALARM: {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="54" />
      <source>Acknowledge</source>
      <translation>Onayla</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="56" />
      <source>Acknowledge all</source>
      <translation>Tümünü onayla</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="37" />
      <source>Active:</source>
      <translation>Etkin:</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="59" />
      <source>Add tool</source>
      <translation>Takım ekle</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="19" />
      <source>Alarm</source>
      <translation>Alarm</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="34" />
      <source>Alarms</source>
      <translation>Alarmlar</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Amax</source>
      <translation>Amax</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="288" />
      <source>An autosave of {0} with unsaved changes exists. Recover it?</source>
      <translation>{0} için kaydedilmemiş değişiklikler içeren otomatik bir kayıt var. Geri yüklensin mi?</translation>
    </message>
    <message>
      <location filename="../../app/widgets/apply_bar.py" line="20" />
      <source>Apply</source>
      <translation>Uygula</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="91" />
      <source>Apply axes</source>
      <translation>Eksenleri uygula</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="163" />
      <source>Apply parameters</source>
      <translation>Parametreleri uygula</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="88" />
      <source>Apply the changed axis definitions?</source>
      <translation>Değiştirilen eksen tanımları uygulansın mı?</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="160" />
      <source>Apply the changed parameters?</source>
      <translation>Değiştirilen parametreler uygulansın mı?</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="24" />
      <source>Auto</source>
      <translation>Otomatik</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="31" />
      <source>Axes</source>
      <translation>Eksenler</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="24" />
      <source>Axis</source>
      <translation>Eksen</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="67" />
      <source>Block delete (/)</source>
      <translation>Blok atlama (/)</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="106" />
      <source>Bus</source>
      <translation>Veri yolu</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="73" />
      <source>Bus {0} ({1}): {2}. Buffer {3} set-points, late cycles {4}, period p99 {5:.1f} µs, max jitter {7:.0f} µs. {6}</source>
      <translation>Veri yolu {0} ({1}): {2}. Tampon {3} hedef nokta, geciken çevrim {4}, periyot p99 {5:.1f} µs, en büyük sapma {7:.0f} µs. {6}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="158" />
      <source>Bus {0}: {1}</source>
      <translation>Veri yolu {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="272" />
      <source>CCW</source>
      <translation>Saat yönü tersi</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="53" />
      <source>CCW (M04)</source>
      <translation>Sol (M04)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="272" />
      <source>CW</source>
      <translation>Saat yönü</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="53" />
      <source>CW (M03)</source>
      <translation>Sağ (M03)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="254" />
      <source>Cancel</source>
      <translation>İptal</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>Cause</source>
      <translation>Neden</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="112" />
      <source>Change service password</source>
      <translation>Servis şifresini değiştir</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="187" />
      <source>Checking {0} …</source>
      <translation>{0} denetleniyor …</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="208" />
      <source>Checking {0} … {1} %</source>
      <translation>{0} denetleniyor … %{1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/preview.py" line="44" />
      <source>Clear</source>
      <translation>Temizle</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="66" />
      <source>Clear G92</source>
      <translation>G92'yi sil</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="74" />
      <source>Connect</source>
      <translation>Bağlan</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="93" />
      <source>Connect to the drives</source>
      <translation>Sürücülere bağlan</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="74" />
      <source>Connect to the drives and enable them?</source>
      <translation>Sürücülere bağlanılıp etkinleştirilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/widgets/jog_panel.py" line="36" />
      <source>Continuous</source>
      <translation>Sürekli</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="84" />
      <source>Corner tolerance (G64)</source>
      <translation>Köşe toleransı (G64)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="107" />
      <source>Count parts from 0 again ({0} counted)?</source>
      <translation>Parçalar yeniden 0'dan sayılsın mı ({0} sayıldı)?</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Counts/unit</source>
      <translation>Sayım/birim</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="182" />
      <source>Current service password:</source>
      <translation>Mevcut servis şifresi:</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="33" />
      <source>Cycle start</source>
      <translation>Çevrim başlat</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="214" />
      <source>Cycle start refused: the program has errors (line {0})</source>
      <translation>Çevrim başlatma reddedildi: programda hata var (satır {0})</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="24" />
      <source>Cycle time</source>
      <translation>Çevrim süresi</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="79" />
      <source>Cycle time Ts</source>
      <translation>Çevrim süresi Ts</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="171" />
      <source>Cycle time {0}; limits Vmax {1:g} mm/s, Amax {2:g} mm/s², Jmax {3:g} mm/s³</source>
      <translation>Çevrim süresi {0}; sınırlar Vmax {1:g} mm/s, Amax {2:g} mm/s², Jmax {3:g} mm/s³</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="31" />
      <source>Cycle timing: start jitter histogram (µs)</source>
      <translation>Çevrim zamanlaması: başlangıç sapması histogramı (µs)</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="147" />
      <source>Delete</source>
      <translation>Sil</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="146" />
      <source>Delete {0} from the tool table?</source>
      <translation>{0} takım tablosundan silinsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="29" />
      <source>Description</source>
      <translation>Açıklama</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="111" />
      <source>Description:</source>
      <translation>Açıklama:</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="33" />
      <source>Diagnostics</source>
      <translation>Tanılama</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="29" />
      <source>Diameter (mm)</source>
      <translation>Çap (mm)</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="14" />
      <source>Direction</source>
      <translation>Yön</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="231" />
      <source>Discard</source>
      <translation>Vazgeç</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="72" />
      <source>Disconnect</source>
      <translation>Bağlantıyı kes</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="93" />
      <source>Disconnect the drives</source>
      <translation>Sürücülerin bağlantısını kes</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="18" />
      <source>Disconnected</source>
      <translation>Bağlı değil</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Drive</source>
      <translation>Sürücü</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="163" />
      <source>E-STOP</source>
      <translation>ACİL STOP</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="26" />
      <source>E-stop</source>
      <translation>Acil stop</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="62" />
      <source>E-stop pressed</source>
      <translation>Acil stop basıldı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="64" />
      <source>E-stop pressed {0}</source>
      <translation>Acil stop basıldı {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="63" />
      <source>E-stop pressed: {0}</source>
      <translation>Acil stop basıldı: {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="61" />
      <source>E-stop: quick stop of all axes ({0})</source>
      <translation>Acil stop: tüm eksenler hızlı durduruldu ({0})</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="64" />
      <source>EtherCAT</source>
      <translation>EtherCAT</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="118" />
      <source>Export failed</source>
      <translation>Dışa aktarma başarısız</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="50" />
      <source>Export log</source>
      <translation>Kaydı dışa aktar</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="16" />
      <source>FE window</source>
      <translation>Takip hatası penceresi</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="484" />
      <source>Feed F{0:.0f} programmed, {1} now</source>
      <translation>İlerleme F{0:.0f} programlanan, şimdi {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="34" />
      <source>Feed hold</source>
      <translation>İlerleme durdur</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="131" />
      <source>Feed override</source>
      <translation>İlerleme oranı</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="60" />
      <source>File name in {0}:</source>
      <translation>{0} içinde dosya adı:</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="36" />
      <source>Find</source>
      <translation>Bul</translation>
    </message>
    <message>
      <location filename="../../app/widgets/find_bar.py" line="20" />
      <source>Find…</source>
      <translation>Bul…</translation>
    </message>
    <message>
      <location filename="../../app/pages/preview.py" line="37" />
      <source>Fit</source>
      <translation>Sığdır</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="77" />
      <source>G-code block, e.g. G01 X10 F600</source>
      <translation>G-kodu bloğu, ör. G01 X10 F600</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="105" />
      <source>G92 offset: off</source>
      <translation>G92 ofseti: kapalı</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="108" />
      <source>G92 offset: {0} (on: every work position is shifted by it)</source>
      <translation>G92 ofseti: {0} (açık: her iş konumu bu kadar kayar)</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="36" />
      <source>Go to line</source>
      <translation>Satıra git</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="144" />
      <source>Held by feed override 0 %</source>
      <translation>İlerleme ayarı %0 ile bekliyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="38" />
      <source>Home</source>
      <translation>Referansla</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="51" />
      <source>Home all axes</source>
      <translation>Tüm eksenleri referansla</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="69" />
      <source>Home all axes? The axes may move.</source>
      <translation>Tüm eksenler referanslansın mı? Eksenler hareket edebilir.</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="64" />
      <source>Home axis</source>
      <translation>Ekseni referansla</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="65" />
      <source>Home axis {0}? The axis may move.</source>
      <translation>{0} ekseni referanslansın mı? Eksen hareket edebilir.</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="24" />
      <source>Homed</source>
      <translation>Referanslı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="102" />
      <source>Homing</source>
      <translation>Referanslama</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="100" />
      <source>Homing required before a program</source>
      <translation>Programdan önce referanslama gerekli</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="86" />
      <source>Homing: {0}; {1}.</source>
      <translation>Referanslama: {0}; {1}.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="18" />
      <source>Idle</source>
      <translation>Hazır</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="212" />
      <source>Import .tbl</source>
      <translation>.tbl içe aktar</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="61" />
      <source>In the spindle</source>
      <translation>İş milinde</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="96" />
      <source>In the spindle: {0}</source>
      <translation>İş milinde: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="97" />
      <source>Interpolation</source>
      <translation>İnterpolasyon</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Jmax</source>
      <translation>Jmax</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="37" />
      <source>Jog</source>
      <translation>Elle hareket</translation>
    </message>
    <message>
      <location filename="../../app/widgets/jog_panel.py" line="56" />
      <source>Jog speed</source>
      <translation>Elle hareket hızı</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="82" />
      <source>Keyboard</source>
      <translation>Klavye</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="14" />
      <source>Kind</source>
      <translation>Tür</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="29" />
      <source>Length Z (mm)</source>
      <translation>Boy Z (mm)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="24" />
      <source>Line</source>
      <translation>Satır</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="464" />
      <source>Line {0}   Progress {1:.0f} %
Remaining {2}   Path speed {3}</source>
      <translation>Satır {0}   Tamamlanan %{1:.0f}
Kalan {2}   Yol hızı {3}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="229" />
      <source>Line {0}: {1}</source>
      <translation>Satır {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="37" />
      <source>Load into machine</source>
      <translation>Makineye yükle</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="115" />
      <source>Lock service level</source>
      <translation>Servis seviyesini kilitle</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="114" />
      <source>M06: the spindle stops for the tool change</source>
      <translation>M06: takım değişimi için iş mili durur</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="96" />
      <source>M66 (line {0}): input P{1} timed out after {2} s: #5399 = -1</source>
      <translation>M66 (satır {0}): P{1} girişi {2} s sonra zaman aşımına uğradı: #5399 = -1</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="72" />
      <source>MDI</source>
      <translation>MDI</translation>
    </message>
    <message>
      <location filename="../../app/widgets/tracking_view.py" line="104" />
      <source>MSE</source>
      <translation>MSE</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="115" />
      <source>Machine</source>
      <translation>Makine</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="24" />
      <source>Machine position</source>
      <translation>Makine konumu</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="28" />
      <source>Machine zero</source>
      <translation>Makine sıfırı</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="74" />
      <source>Make the current position of {0} its machine zero?</source>
      <translation>{0} ekseninin şu anki konumu makine sıfırı yapılsın mı?</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="25" />
      <source>Manual</source>
      <translation>Manuel</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Max</source>
      <translation>En büyük</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="196" />
      <source>Measure on the setter</source>
      <translation>Ayarlayıcıda ölç</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="193" />
      <source>Measure {0} on the tool setter? The spindle goes up to the clearance height, across to the setter and probes down onto it twice. Keep clear of the machine.</source>
      <translation>{0} takım ayarlayıcıda ölçülsün mü? İş mili emniyet yüksekliğine çıkar, ayarlayıcının üzerine gider ve iki kez aşağı doğru problar. Makineden uzak durun.</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Min</source>
      <translation>En küçük</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="172" />
      <source>Network adapter</source>
      <translation>Ağ bağdaştırıcısı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="173" />
      <source>Network interface of the EtherCAT bus:</source>
      <translation>EtherCAT veri yolunun ağ arayüzü:</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="35" />
      <source>New</source>
      <translation>Yeni</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="185" />
      <source>New service password (at least {0} characters):</source>
      <translation>Yeni servis şifresi (en az {0} karakter):</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="133" />
      <source>New tool number</source>
      <translation>Yeni takım numarası</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="26" />
      <source>No</source>
      <translation>Hayır</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="70" />
      <source>No program loaded.</source>
      <translation>Yüklü program yok.</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="177" />
      <source>No tool is in the spindle.</source>
      <translation>İş milinde takım yok.</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="163" />
      <source>No tool is in the spindle: put {0} in and set it (In the spindle) first.</source>
      <translation>İş milinde takım yok: önce {0} takın ve ayarlayın (İş milinde).</translation>
    </message>
    <message>
      <location filename="../../app/widgets/keypad.py" line="96" />
      <source>Not a number</source>
      <translation>Sayı değil</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="196" />
      <source>Nothing changed: {0}</source>
      <translation>Hiçbir şey değişmedi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/keypad.py" line="18" />
      <source>OK</source>
      <translation>Tamam</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="30" />
      <source>OPC UA</source>
      <translation>OPC UA</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="102" />
      <source>OPC UA server: not serving: {0}</source>
      <translation>OPC UA sunucusu: hizmet vermiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="100" />
      <source>OPC UA server: off ([opcua] enabled = false)</source>
      <translation>OPC UA sunucusu: kapalı ([opcua] enabled = false)</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="110" />
      <source>OPC UA server: serving {0} ({1}), certificate SHA-1 {2}</source>
      <translation>OPC UA sunucusu: {0} adresinde hizmet veriyor ({1}), sertifika SHA-1 {2}</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="106" />
      <source>OPC UA server: serving {0} with security None: anyone who reaches the port reads the machine</source>
      <translation>OPC UA sunucusu: {0} adresinde güvenliksiz (None) hizmet veriyor: bağlantı noktasına ulaşan herkes makineyi okuyabilir</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="104" />
      <source>OPC UA server: starting at {0}</source>
      <translation>OPC UA sunucusu: {0} adresinde başlıyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="53" />
      <source>Off (M05)</source>
      <translation>Kapalı (M05)</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="51" />
      <source>Open file</source>
      <translation>Dosya aç</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="51" />
      <source>Open program</source>
      <translation>Program aç</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="35" />
      <source>Open…</source>
      <translation>Aç…</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="119" />
      <source>Optional stop</source>
      <translation>İsteğe bağlı duruş</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="23" />
      <source>Optional stop (M1)</source>
      <translation>İsteğe bağlı duruş (M1)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="249" />
      <source>Or start it again from line 1, from where the tool stands now.</source>
      <translation>Ya da programı takımın şu anki yerinden, 1. satırdan yeniden başlatın.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/keypad.py" line="99" />
      <source>Out of range: {0} to {1}</source>
      <translation>Aralık dışında: {0} ile {1} arası</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="32" />
      <source>Parameters</source>
      <translation>Parametreler</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="24" />
      <source>Part</source>
      <translation>Parça</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="29" />
      <source>Part zero</source>
      <translation>Parça sıfırı</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="98" />
      <source>Parts to make (0: no target)</source>
      <translation>Yapılacak parça (0: hedef yok)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="82" />
      <source>Parts: {0}</source>
      <translation>Parça: {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="81" />
      <source>Parts: {0} of {1}</source>
      <translation>Parça: {0} / {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="29" />
      <source>Path acceleration Amax</source>
      <translation>Yol ivmesi Amax</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="30" />
      <source>Path jerk Jmax</source>
      <translation>Yol sarsıntısı Jmax</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="28" />
      <source>Path speed Vmax</source>
      <translation>Yol hızı Vmax</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="64" />
      <source>Path v / a / j</source>
      <translation>Yol v / a / j</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="143" />
      <source>Planned when this page is shown.</source>
      <translation>Bu sayfa gösterildiğinde planlanır.</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="92" />
      <source>Planner mode</source>
      <translation>Planlayıcı kipi</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="150" />
      <source>Planning…</source>
      <translation>Planlanıyor…</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="29" />
      <source>Pocket</source>
      <translation>Cep</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="11" />
      <source>Position</source>
      <translation>Konum</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="27" />
      <source>Preview</source>
      <translation>Önizleme</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="70" />
      <source>Probe input: free</source>
      <translation>Prob girişi: serbest</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="71" />
      <source>Probe input: none ([probe] drive in the machine configuration)</source>
      <translation>Prob girişi: yok (makine yapılandırmasında [probe] drive)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="70" />
      <source>Probe input: touching</source>
      <translation>Prob girişi: temas ediyor</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="11" />
      <source>Product</source>
      <translation>Ürün</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="65" />
      <source>Production</source>
      <translation>Üretim</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="26" />
      <source>Program</source>
      <translation>Program</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="412" />
      <source>Program finished in {0}</source>
      <translation>Program {0} sürede bitti</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="222" />
      <source>Program loaded: {0}</source>
      <translation>Program yüklendi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="218" />
      <source>Program loaded: {0}; G64: {1} corners smoothed, at most {2:.3f} mm from the programmed path</source>
      <translation>Program yüklendi: {0}; G64: {1} köşe yumuşatıldı, programlanan yoldan en çok {2:.3f} mm</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="235" />
      <source>Program refused: {0} error(s)</source>
      <translation>Program reddedildi: {0} hata</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="22" />
      <source>Program stop (M0)</source>
      <translation>Program duruşu (M0)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="417" />
      <source>Program stopped at line {0}: {1}</source>
      <translation>Program {0}. satırda durdu: {1}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="163" />
      <source>RELEASE
E-STOP</source>
      <translation>ACİL STOP
BIRAK</translation>
    </message>
    <message>
      <location filename="../../app/widgets/tracking_view.py" line="104" />
      <source>RMSE</source>
      <translation>RMSE</translation>
    </message>
    <message>
      <location filename="../../app/widgets/keypad.py" line="48" />
      <source>Range: {0} to {1}</source>
      <translation>Aralık: {0} ile {1} arası</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="134" />
      <source>Rapid override</source>
      <translation>Hızlı hareket oranı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="31" />
      <source>Rapid speed</source>
      <translation>Hızlı hareket hızı</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="288" />
      <source>Recover</source>
      <translation>Geri yükle</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="124" />
      <source>Refused: {0}</source>
      <translation>Reddedildi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="123" />
      <source>Release E-stop</source>
      <translation>Acil stopu bırak</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="124" />
      <source>Release the emergency stop and enable the drives?</source>
      <translation>Acil stop bırakılıp sürücüler etkinleştirilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="80" />
      <source>Reload</source>
      <translation>Yeniden yükle</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="189" />
      <source>Repeat the new password:</source>
      <translation>Yeni şifreyi tekrarlayın:</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="212" />
      <source>Replace the whole tool table by {0}?</source>
      <translation>Tüm takım tablosu {0} ile değiştirilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="58" />
      <source>Reset</source>
      <translation>Sıfırla</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="46" />
      <source>Reset counter</source>
      <translation>Sayacı sıfırla</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="24" />
      <source>Result</source>
      <translation>Sonuç</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="253" />
      <source>Resume at line {0}</source>
      <translation>{0}. satırdan devam et</translation>
    </message>
    <message>
      <location filename="../../app/widgets/apply_bar.py" line="22" />
      <source>Revert</source>
      <translation>Geri al</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="297" />
      <source>Run from line</source>
      <translation>Satırdan çalıştır</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="302" />
      <source>Run from line refused: {0}</source>
      <translation>Satırdan çalıştırma reddedildi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="507" />
      <source>Run from line: {0}</source>
      <translation>Satırdan çalıştır: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="125" />
      <source>Run from line…</source>
      <translation>Satırdan çalıştır…</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="120" />
      <source>Run log exported</source>
      <translation>Çalışma kaydı dışa aktarıldı</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="230" />
      <source>Run the program anyway?</source>
      <translation>Program yine de çalıştırılsın mı?</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="308" />
      <source>Run the program from line {0}?</source>
      <translation>Program {0}. satırdan çalıştırılsın mı?</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="19" />
      <source>Running</source>
      <translation>Çalışıyor</translation>
    </message>
    <message>
      <location filename="../../app/widgets/tracking_view.py" line="112" />
      <source>Samples: {0}</source>
      <translation>Örnek sayısı: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="35" />
      <source>Save</source>
      <translation>Kaydet</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="35" />
      <source>Save as…</source>
      <translation>Farklı kaydet…</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="334" />
      <source>Save failed</source>
      <translation>Kaydetme başarısız</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="60" />
      <source>Save program as</source>
      <translation>Programı farklı kaydet</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="304" />
      <source>Save with errors?</source>
      <translation>Hatalarla kaydedilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="79" />
      <source>Send</source>
      <translation>Gönder</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="119" />
      <source>Service</source>
      <translation>Servis</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="267" />
      <source>Service level</source>
      <translation>Servis seviyesi</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="296" />
      <source>Service level locked after {0} minutes without input</source>
      <translation>Servis seviyesi {0} dakika işlem yapılmadığı için kilitlendi</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="272" />
      <source>Service level refused: {0}</source>
      <translation>Servis seviyesi reddedildi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="274" />
      <source>Service level unlocked</source>
      <translation>Servis seviyesi açıldı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="182" />
      <source>Service password</source>
      <translation>Servis şifresi</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="267" />
      <source>Service password:</source>
      <translation>Servis şifresi:</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="40" />
      <source>Set here as zero</source>
      <translation>Burayı sıfır yap</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="73" />
      <source>Set machine zero</source>
      <translation>Makine sıfırını ayarla</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>Severity</source>
      <translation>Önem</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="52" />
      <source>Show history</source>
      <translation>Geçmişi göster</translation>
    </message>
    <message>
      <location filename="../../app/pages/preview.py" line="40" />
      <source>Show in program</source>
      <translation>Programda göster</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="115" />
      <source>Single block</source>
      <translation>Tek blok</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>Source</source>
      <translation>Kaynak</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="49" />
      <source>Spindle</source>
      <translation>İş mili</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="480" />
      <source>Spindle off</source>
      <translation>İş mili durdu</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="137" />
      <source>Spindle override</source>
      <translation>İş mili oranı</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="60" />
      <source>Spindle speed</source>
      <translation>İş mili devri</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="481" />
      <source>Spindle {0} {1:.0f} rpm</source>
      <translation>İş mili {0} {1:.0f} dev/dk</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="135" />
      <source>Spindle: {0}, {1:.0f} rpm</source>
      <translation>İş mili: {0}, {1:.0f} dev/dak</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="24" />
      <source>Start</source>
      <translation>Başlangıç</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="240" />
      <source>Start from the beginning</source>
      <translation>Baştan başlat</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>State</source>
      <translation>Durum</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="35" />
      <source>Stop</source>
      <translation>Dur</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="72" />
      <source>Stop and disable the drives?</source>
      <translation>Sürücüler durdurulup devre dışı bırakılsın mı?</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="23" />
      <source>Stopping</source>
      <translation>Duruyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="52" />
      <source>Tap a value to change it. Lengths are the tool's Z offset, used by G43. Touch off: jog the tool tip onto a surface and enter its height in the active work coordinates.</source>
      <translation>Değiştirmek için bir değere dokunun. Boy, takımın G43 ile kullanılan Z ofsetidir. Dokunarak ölçme: takım ucunu bir yüzeye getirin ve yüzeyin etkin iş koordinatlarındaki yüksekliğini girin.</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="29" />
      <source>Tap a value to change it. Units: mm for linear axes, degrees for rotary axes. Changes take effect after Apply (written atomically).</source>
      <translation>Değiştirmek için bir değere dokunun. Birimler: doğrusal eksenlerde mm, döner eksenlerde derece. Değişiklikler Uygula'dan sonra geçerli olur (atomik olarak yazılır).</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="57" />
      <source>Tap a value to type it. Touch off: the current position becomes the work coordinate you enter, in the selected offset.</source>
      <translation>Yazmak için bir değere dokunun. Dokunarak sıfırlama: şu anki konum, seçili ofsette girdiğiniz iş koordinatı olur.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="42" />
      <source>Target…</source>
      <translation>Hedef…</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="175" />
      <source>The control did not shut down cleanly: home the axes (Machine zero, Home all) before running a program</source>
      <translation>Kontrol düzgün kapanmadı: program çalıştırmadan önce eksenleri referanslayın (Makine sıfırı, Tüm eksenleri referansla)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="268" />
      <source>The machine goes there the way drawn</source>
      <translation>Makine oraya çizilen yoldan gider</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="265" />
      <source>The machine goes up to Z{0:.3f} (machine), across, then down to it the way drawn</source>
      <translation>Makine Z{0:.3f} (makine) yüksekliğine çıkar, yatay gider, sonra çizilen yoldan oraya iner</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="90" />
      <source>The machine is moving.</source>
      <translation>Makine hareket ediyor.</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="247" />
      <source>The program stopped at line {0} ({1}).</source>
      <translation>Program {0}. satırda durdu ({1}).</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="242" />
      <source>The program stopped at line {0} and cannot resume there: {1}</source>
      <translation>Program {0}. satırda durdu ve oradan devam edemez: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="194" />
      <source>The service password was changed.</source>
      <translation>Servis şifresi değiştirildi.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/service_gate.py" line="28" />
      <source>This page changes the machine configuration. Enter the service password.</source>
      <translation>Bu sayfa makine yapılandırmasını değiştirir. Servis şifresini girin.</translation>
    </message>
    <message>
      <location filename="../../app/pages/placeholder.py" line="19" />
      <source>This page is not built yet.</source>
      <translation>Bu sayfa henüz hazır değil.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="72" />
      <source>This run ends about {0} ({1} from now)</source>
      <translation>Bu çalışma yaklaşık {0} saatinde biter ({1} sonra)</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>Time</source>
      <translation>Zaman</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="115" />
      <source>To go</source>
      <translation>Kalan</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="29" />
      <source>Tool</source>
      <translation>Takım</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="23" />
      <source>Tool change</source>
      <translation>Takım değişimi</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="483" />
      <source>Tool {0}</source>
      <translation>Takım {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="169" />
      <source>Tool: {0}</source>
      <translation>Takım: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="30" />
      <source>Tools</source>
      <translation>Takımlar</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="62" />
      <source>Touch off length</source>
      <translation>Boyu dokunarak ölç</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="75" />
      <source>Touch off {0}</source>
      <translation>{0} dokunarak sıfırla</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="181" />
      <source>Touch off {0}: work Z of the surface the tip touches</source>
      <translation>{0} dokunarak ölç: ucun değdiği yüzeyin iş Z'si</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="139" />
      <source>Touch off {0}: work coordinate here</source>
      <translation>{0} dokunarak sıfırla: buradaki iş koordinatı</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="64" />
      <source>Tracking</source>
      <translation>Takip</translation>
    </message>
    <message>
      <location filename="../../app/widgets/tracking_view.py" line="60" />
      <source>Tracking (reference − actual), Eq. 18</source>
      <translation>Takip (referans − gerçek), Denklem 18</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="111" />
      <source>T{0}</source>
      <translation>T{0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="138" />
      <source>T{0} is already in the table.</source>
      <translation>T{0} tabloda zaten var.</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="51" />
      <source>T{0} is in the spindle: set another tool first</source>
      <translation>T{0} iş milinde: önce başka bir takım seçin</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="98" />
      <source>T{0} is not in the spindle: put it in and set it (In the spindle) first</source>
      <translation>T{0} iş milinde değil: önce takın ve ayarlayın (İş milinde)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="50" />
      <source>T{0} is not in the tool table</source>
      <translation>T{0} takım tablosunda yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="111" />
      <source>T{0} length {1} mm is longer than the Z travel ({2} mm): check the value and the surface it was touched off on</source>
      <translation>T{0} boyu {1} mm, Z hareket aralığından ({2} mm) uzun: değeri ve dokundurulduğu yüzeyi kontrol edin</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="97" />
      <source>T{0} measured on the tool setter: length {1} mm</source>
      <translation>T{0} takım ayarlayıcıda ölçüldü: boy {1} mm</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="118" />
      <source>T{0}: diameter (mm)</source>
      <translation>T{0}: çap (mm)</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="117" />
      <source>T{0}: length Z (mm)</source>
      <translation>T{0}: boy Z (mm)</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="116" />
      <source>T{0}: pocket</source>
      <translation>T{0}: cep</translation>
    </message>
    <message>
      <location filename="../../app/widgets/service_gate.py" line="31" />
      <source>Unlock</source>
      <translation>Kilidi aç</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="229" />
      <source>Unsaved changes</source>
      <translation>Kaydedilmemiş değişiklikler</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="11" />
      <source>Vendor</source>
      <translation>Üretici</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Vmax</source>
      <translation>Vmax</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="61" />
      <source>Work</source>
      <translation>İş</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="42" />
      <source>Work = tool tip in {0}</source>
      <translation>İş = takım ucu, {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/preview.py" line="105" />
      <source>Work coordinates ({0}): the cross is the work zero, the dashed box the machine's travel.</source>
      <translation>İş koordinatları ({0}): artı işareti iş sıfırı, kesikli kutu makinenin hareket alanı.</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="118" />
      <source>XY rotation (°)</source>
      <translation>XY dönüşü (°)</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="111" />
      <source>XY rotation of {0}: {1} degrees</source>
      <translation>{0} XY döndürmesi: {1} derece</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="35" />
      <source>XY turned {0:g}°</source>
      <translation>XY {0:g}° döndürülmüş</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="25" />
      <source>Yes</source>
      <translation>Evet</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="93" />
      <source>a probe move ended without the probe armed: the program stops here</source>
      <translation>bir prob hareketi prob kurulmadan bitti: program burada durur</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="36" />
      <source>acknowledge the active alarms first</source>
      <translation>önce etkin alarmları onaylayın</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="104" />
      <source>acknowledged</source>
      <translation>onaylandı</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="104" />
      <source>active</source>
      <translation>etkin</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="55" />
      <source>alarm</source>
      <translation>alarm</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="43" />
      <source>another tool is in the spindle since it was loaded</source>
      <translation>program yüklendiğinden beri iş milinde başka bir takım var</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="71" />
      <source>axes are not homed any more: home them before running a program</source>
      <translation>eksenler artık referanslı değil: program çalıştırmadan önce referanslayın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="34" />
      <source>axes not homed</source>
      <translation>eksenler referanslanmadı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="33" />
      <source>axes not homed: {0} (home them or set machine zero first)</source>
      <translation>eksenler referanslanmadı: {0} (önce referanslayın ya da makine sıfırını ayarlayın)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="69" />
      <source>axis {0} did not reach OPERATION ENABLED within {1} s (drive state {2})</source>
      <translation>{0} ekseni {1} s içinde OPERATION ENABLED durumuna geçmedi (sürücü durumu {2})</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="27" />
      <source>bus</source>
      <translation>veri yolu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="119" />
      <source>column {0}: {1}</source>
      <translation>sütun {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="88" />
      <source>completed</source>
      <translation>tamamlandı</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="28" />
      <source>configuration</source>
      <translation>yapılandırma</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="72" />
      <source>connected</source>
      <translation>bağlı</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="28" />
      <source>controller</source>
      <translation>denetleyici</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="55" />
      <source>disconnected</source>
      <translation>bağlı değil</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="59" />
      <source>drive fault on axis {0} (slave {1}): error code {2}: quick stop of all axes</source>
      <translation>{0} ekseninde sürücü hatası (bağımlı {1}): hata kodu {2}: tüm eksenler hızlı durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="83" />
      <source>drive homing method {0}</source>
      <translation>sürücü referanslama yöntemi {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="37" />
      <source>drive {0}</source>
      <translation>sürücü {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="55" />
      <source>e-stop</source>
      <translation>acil stop</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="26" />
      <source>feed hold</source>
      <translation>ilerleme durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="113" />
      <source>feed move with the spindle stopped: the M6 at line {0} stopped it and no M3/M4 started it again</source>
      <translation>iş mili dururken ilerleme hareketi: {0}. satırdaki M6 onu durdurdu ve hiçbir M3/M4 yeniden başlatmadı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="44" />
      <source>feed override must be 0-{0} %, got {1}</source>
      <translation>ilerleme oranı %0-{0} olmalı, {1} verildi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="46" />
      <source>feed override {0} % capped at {1} % here: the machine's speed, acceleration or jerk limit</source>
      <translation>ilerleme oranı %{0} burada %{1} ile sınırlandı: makinenin hız, ivme ya da sarsıntı sınırı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="57" />
      <source>following error on axis {0}: {1} exceeds window {2} for more than {3} cycles: quick stop of all axes</source>
      <translation>{0} ekseninde takip hatası: {1}, {2} penceresini {3} çevrimden uzun aştı: tüm eksenler hızlı durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="55" />
      <source>hold</source>
      <translation>beklemede</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="55" />
      <source>homing</source>
      <translation>referanslanıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="66" />
      <source>homing of axis {0} failed ({1})</source>
      <translation>{0} ekseninin referanslanması başarısız ({1})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="55" />
      <source>idle</source>
      <translation>boşta</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="25" />
      <source>info</source>
      <translation>bilgi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="94" />
      <source>line {0} comes after the probe at line {1}: what follows depends on what it read; run from line {1} (or before) to read it again</source>
      <translation>satır {0}, satır {1}'deki probdan sonra geliyor: devamı onun okuduğuna bağlı; yeniden okumak için satır {1}'den (veya öncesinden) çalıştırın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="52" />
      <source>line {0} needs T{1} in the spindle (T{2} is in it): put it in and set it on the Tools page, or run from the M6 line {3}</source>
      <translation>{0}. satır için iş milinde T{1} gerekli (şu an T{2} takılı): takın ve Takımlar sayfasında seçin ya da {3}. satırdaki M6 satırından çalıştırın</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="56" />
      <source>linear</source>
      <translation>doğrusal</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="31" />
      <source>machine is {0}</source>
      <translation>makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/widgets/tracking_view.py" line="104" />
      <source>max |e|</source>
      <translation>en büyük |e|</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="92" />
      <source>measuring tool T{0}</source>
      <translation>T{0} takımı ölçülüyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="81" />
      <source>no</source>
      <translation>hayır</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="35" />
      <source>no program loaded</source>
      <translation>yüklü program yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="101" />
      <source>no program stopped part-way</source>
      <translation>yarıda durmuş bir program yok</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="41" />
      <source>no tool length offset</source>
      <translation>takım boy ofseti yok</translation>
    </message>
    <message>
      <location filename="../../app/format.py" line="43" />
      <source>none</source>
      <translation>yok</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="72" />
      <source>not connected</source>
      <translation>bağlı değil</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="32" />
      <source>nothing to hold: machine is {0}</source>
      <translation>durdurulacak bir şey yok: makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="134" />
      <source>off</source>
      <translation>kapalı</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="28" />
      <source>operator</source>
      <translation>operatör</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="85" />
      <source>optional</source>
      <translation>isteğe bağlı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="23" />
      <source>optional stop (M01, line {0}): press cycle start</source>
      <translation>isteğe bağlı duruş (M01, satır {0}): çevrim başlata basın</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="31" />
      <source>outputs</source>
      <translation>çıkışlar</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="27" />
      <source>planner</source>
      <translation>planlayıcı</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="29" />
      <source>probe</source>
      <translation>prob</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="30" />
      <source>program</source>
      <translation>program</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="29" />
      <source>program end</source>
      <translation>program sonu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="22" />
      <source>program paused (M00, line {0}): press cycle start</source>
      <translation>program duraklatıldı (M00, satır {0}): çevrim başlata basın</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="26" />
      <source>quick stop</source>
      <translation>hızlı durdurma</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="65" />
      <source>quick stop of all axes: {0}</source>
      <translation>tüm eksenler hızlı durduruldu: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="85" />
      <source>required before a program may start</source>
      <translation>program başlamadan önce gerekli</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="103" />
      <source>reset</source>
      <translation>sıfırlama</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="56" />
      <source>rotary</source>
      <translation>döner</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="102" />
      <source>run from line {0}</source>
      <translation>{0}. satırdan çalıştırma</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="55" />
      <source>running</source>
      <translation>çalışıyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="84" />
      <source>set current position as zero</source>
      <translation>şu anki konumu sıfır yap</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="68" />
      <source>set-point buffer underrun after {0} set-points: holding the last position</source>
      <translation>{0} hedef noktadan sonra hedef tamponu boşaldı: son konum tutuluyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="25" />
      <source>single block: end of line {0}</source>
      <translation>tek blok: {0}. satırın sonu</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="30" />
      <source>spindle</source>
      <translation>iş mili</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="45" />
      <source>spindle override must be 50-150 %, got {0}</source>
      <translation>iş mili oranı %50-150 olmalı, {0} verildi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="47" />
      <source>spindle override {0} % capped at {1} %: the spindle's maximum is {2} rpm</source>
      <translation>iş mili oranı %{0}, %{1} ile sınırlandı: iş milinin en yüksek hızı {2} dev/dk</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="29" />
      <source>state folder</source>
      <translation>durum klasörü</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="25" />
      <source>stop</source>
      <translation>durdurma</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="28" />
      <source>stopped by the operator</source>
      <translation>operatör tarafından durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="27" />
      <source>stopping</source>
      <translation>duruyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="70" />
      <source>the control did not shut down cleanly (power loss or killed; position last saved {0}): {1}</source>
      <translation>kontrol düzgün kapanmadı (elektrik kesintisi ya da zorla sonlandırma; konum en son {0} tarihinde kaydedildi): {1}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="72" />
      <source>the drives have absolute encoders: homed flags kept</source>
      <translation>sürücülerde mutlak enkoder var: referans bilgisi korundu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="88" />
      <source>the fast probe down to the setter</source>
      <translation>takım ölçere hızlı prob inişi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="41" />
      <source>the machine configuration changed since it was loaded</source>
      <translation>makine ayarları, program yüklendiğinden beri değişti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="39" />
      <source>the machine moved since it was loaded</source>
      <translation>makine, program yüklendiğinden beri hareket etti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="91" />
      <source>the move back up</source>
      <translation>yukarı geri dönüş</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="87" />
      <source>the move over the tool setter</source>
      <translation>takım ölçerin üzerine gidiş</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="89" />
      <source>the move up from the first contact</source>
      <translation>ilk temastan yukarı çıkış</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="86" />
      <source>the move up to the clearance height</source>
      <translation>emniyet yüksekliğine çıkış</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="100" />
      <source>the program stopped at line {0}: resume there or start it again from the beginning (choose one)</source>
      <translation>program {0}. satırda durdu: oradan devam edin ya da baştan başlatın (birini seçin)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="37" />
      <source>the program {0} is still being checked (wait until it is loaded)</source>
      <translation>{0} programı hâlâ denetleniyor (yüklenene kadar bekleyin)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="90" />
      <source>the slow probe down to the setter</source>
      <translation>takım ölçere yavaş prob inişi</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="271" />
      <source>the spindle starts at {0:.0f} rpm {1} before it goes down</source>
      <translation>iş mili inmeden önce {0:.0f} dev/dk {1} döner</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="270" />
      <source>the spindle stays off</source>
      <translation>iş mili kapalı kalır</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="117" />
      <source>the target of {0} part(s) is reached: reset the part counter (or raise the target) to run again</source>
      <translation>{0} parçalık hedefe ulaşıldı: yeniden çalıştırmak için parça sayacını sıfırlayın (ya da hedefi yükseltin)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="104" />
      <source>the tool length offset in force changed since it was loaded</source>
      <translation>yüklendiğinden beri geçerli takım boy ofseti değişti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="48" />
      <source>the tool table cannot change while the machine is {0}: a program reads the offsets when it is checked</source>
      <translation>makine {0} durumundayken takım tablosu değiştirilemez: program, ofsetleri denetlenirken okur</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="42" />
      <source>the tool table changed since it was loaded</source>
      <translation>takım tablosu, program yüklendiğinden beri değişti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="40" />
      <source>the work offsets changed since it was loaded</source>
      <translation>iş ofsetleri, program yüklendiğinden beri değişti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="24" />
      <source>tool change (M06, line {0}): insert tool {1} and press cycle start</source>
      <translation>takım değişimi (M06, satır {0}): {1} takımını takın ve çevrim başlata basın</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="273" />
      <source>tool {0}</source>
      <translation>takım {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="39" />
      <source>tool {0}length {1} mm</source>
      <translation>takım {0}boy {1} mm</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="29" />
      <source>tools</source>
      <translation>takımlar</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="109" />
      <source>touch off {0}: not a number</source>
      <translation>{0} sıfırlama: sayı değil</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="65" />
      <source>unknown</source>
      <translation>bilinmiyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="25" />
      <source>warning</source>
      <translation>uyarı</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="27" />
      <source>worker</source>
      <translation>çevrim işçisi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="60" />
      <source>working counter {0} instead of {1} for more than {2} cycles: quick stop of all axes{3}</source>
      <translation>çalışma sayacı {2} çevrimden uzun süre {1} yerine {0}: tüm eksenler hızlı durduruldu{3}</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="81" />
      <source>yes</source>
      <translation>evet</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="191" />
      <source>{0} (checking…)</source>
      <translation>{0} (denetleniyor…)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="74" />
      <source>{0} (line {1}): contact at {2} (machine)</source>
      <translation>{0} (satır {1}): temas {2} konumunda (makine)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="75" />
      <source>{0} (line {1}): contact lost at {2} (machine)</source>
      <translation>{0} (satır {1}): temas {2} konumunda kesildi (makine)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="76" />
      <source>{0} (line {1}): no contact</source>
      <translation>{0} (satır {1}): temas yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="78" />
      <source>{0} (line {1}): the probe already touches where the move starts</source>
      <translation>{0} (satır {1}): prob, hareketin başladığı yerde zaten temas ediyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="77" />
      <source>{0} (line {1}): the probe move ended without contact</source>
      <translation>{0} (satır {1}): prob hareketi temas olmadan bitti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="79" />
      <source>{0} (line {1}): with the result, {2}</source>
      <translation>{0} (satır {1}): sonuçla birlikte, {2}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="81" />
      <source>{0} ({1}): contact at {2} (machine)</source>
      <translation>{0} ({1}): temas {2} konumunda (makine)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="82" />
      <source>{0} ({1}): no contact</source>
      <translation>{0} ({1}): temas yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="84" />
      <source>{0} ({1}): the probe already touches where the move starts</source>
      <translation>{0} ({1}): prob, hareketin başladığı yerde zaten temas ediyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="83" />
      <source>{0} ({1}): the probe move ended without contact</source>
      <translation>{0} ({1}): prob hareketi temas olmadan bitti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="85" />
      <source>{0} ({1}): with the result, {2}</source>
      <translation>{0} ({1}): sonuçla birlikte, {2}</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="126" />
      <source>{0} XY rotation (degrees, as G10 L2 R)</source>
      <translation>{0} XY dönüşü (derece, G10 L2 R gibi)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="120" />
      <source>{0} and {1}</source>
      <translation>{0} ve {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="187" />
      <source>{0} error(s); first at line {1}: {2}</source>
      <translation>{0} hata; ilki {1}. satırda: {2}</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="230" />
      <source>{0} has unsaved changes.</source>
      <translation>{0} dosyasında kaydedilmemiş değişiklikler var.</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="305" />
      <source>{0} has {1} error(s), the first at line {2}: {3}. Save it anyway?</source>
      <translation>{0} içinde {1} hata var, ilki {2}. satırda: {3}. Yine de kaydedilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="169" />
      <source>{0} is in the spindle, {1} is selected. Whose length is measured?</source>
      <translation>İş milinde {0} var, {1} seçili. Hangisinin boyu ölçülüyor?</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="209" />
      <source>{0} is not a tool table in the program folders</source>
      <translation>{0} program klasörlerinde bir takım tablosu değil</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="147" />
      <source>{0} lines: shown read-only (edit programs of over {1} lines in CAM or on a PC)</source>
      <translation>{0} satır: yalnızca okunur gösteriliyor ({1} satırdan uzun programları CAM'de ya da bir bilgisayarda düzenleyin)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="67" />
      <source>{0} lost: not answering process data; trying to recover it when it comes back</source>
      <translation>{0} kayboldu: süreç verisine yanıt vermiyor; geri geldiğinde kurtarılmaya çalışılacak</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="116" />
      <source>{0} part(s) made: the target of {1} is reached</source>
      <translation>{0} parça yapıldı: {1} hedefine ulaşıldı</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="171" />
      <source>{0} was running at line {1} when the control stopped (power loss or killed): home the axes, open it and run from line {1}</source>
      <translation>Kontrol durduğunda {0} {1}. satırda çalışıyordu (elektrik kesintisi veya sonlandırma): eksenleri referanslayın, programı açın ve {1}. satırdan çalıştırın</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="442" />
      <source>{0} was saved with changes since it was loaded: the machine runs the program as loaded.</source>
      <translation>{0} yüklendikten sonra değişikliklerle kaydedildi: makine programı yüklendiği haliyle çalıştırır.</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="132" />
      <source>{0} {1} (machine coordinate of part zero)</source>
      <translation>{0} {1} (parça sıfırının makine koordinatı)</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="121" />
      <source>{0} {1} ({2}, {3}): {4}</source>
      <translation>{0} {1} ({2}, {3}): {4}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="106" />
      <source>{0} {1} zero would be at machine {2} with the tool length offset in force, outside the travel {3} .. {4} {5}</source>
      <translation>{0} {1} sıfırı, geçerli takım boy ofsetiyle makinede {2} konumunda olurdu, {3} .. {4} {5} hareket aralığının dışında</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="108" />
      <source>{0} {1} zero would be at machine {2}, outside the travel {3} .. {4} {5}</source>
      <translation>{0} {1} sıfırı makinede {2} konumunda olurdu, {3} .. {4} {5} hareket aralığının dışında</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="110" />
      <source>{0}: not a number</source>
      <translation>{0}: sayı değil</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="504" />
      <source>{0}: {1}</source>
      <translation>{0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="38" />
      <source>{0}: {1} is being checked again; it starts when ready</source>
      <translation>{0}: {1} yeniden denetleniyor; hazır olunca başlayacak</translation>
    </message>
  </context>
</TS>
