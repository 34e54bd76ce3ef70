<?xml version="1.0" encoding="utf-8"?>
<!DOCTYPE TS>
<TS version="2.1" language="tr">
  <context>
    <name>cnc</name>
    <message>
      <location filename="../../app/widgets/status_header.py" line="256" />
      <source> (+{0} more)</source>
      <translation> (+{0} tane daha)</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="192" />
      <source> (first {0:.0f} s shown)</source>
      <translation> (ilk {0:.0f} s gösteriliyor)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="215" />
      <source>'%' must be alone on its line</source>
      <translation>'%' kendi satırında tek başına olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="216" />
      <source>')' without '('</source>
      <translation>'(' olmadan ')'</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="217" />
      <source>(ABORT comment): </source>
      <translation>(ABORT açıklaması): </translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="489" />
      <source>/ lines skipped</source>
      <translation>/ satırları atlanıyor</translation>
    </message>
    <message>
      <location filename="../../app/widgets/keypad.py" line="104" />
      <source>A whole number: {0} has a fraction</source>
      <translation>Bir tam sayı olmalı: {0} kesirli</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="257" />
      <source>ALARM: {0}: {1}</source>
      <translation>ALARM: {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="42" />
      <source>Acknowledge</source>
      <translation>Onayla</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="44" />
      <source>Acknowledge all</source>
      <translation>Tümünü onayla</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="52" />
      <source>Active:</source>
      <translation>Etkin:</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="59" />
      <source>Add tool</source>
      <translation>Takım ekle</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="20" />
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
      <location filename="../../app/pages/program.py" line="290" />
      <source>An autosave of {0} with unsaved changes exists. Recover it?</source>
      <translation>{0} için kaydedilmemiş değişiklikler içeren otomatik bir kayıt var. Geri yüklensin mi?</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="13" />
      <source>Angle of a face</source>
      <translation>Yüz açısı</translation>
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
      <location filename="../../app/pages/parameters.py" line="179" />
      <source>Apply parameters</source>
      <translation>Parametreleri uygula</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="88" />
      <source>Apply the changed axis definitions?</source>
      <translation>Değiştirilen eksen tanımları uygulansın mı?</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="176" />
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
      <location filename="../../app/pages/machine_zero.py" line="32" />
      <source>Axis</source>
      <translation>Eksen</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="69" />
      <source>Block delete (/)</source>
      <translation>Blok atlama (/)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="14" />
      <source>Bore centre</source>
      <translation>Delik merkezi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="15" />
      <source>Boss centre</source>
      <translation>Çıkıntı merkezi</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="121" />
      <source>Bus</source>
      <translation>Veri yolu</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="104" />
      <source>Bus {0} ({1}): {2}. Buffer {3} set-points, late cycles {4}, period p99 {5:.1f} µs, max jitter {7:.0f} µs. {6}</source>
      <translation>Veri yolu {0} ({1}): {2}. Tampon {3} hedef nokta, geciken çevrim {4}, periyot p99 {5:.1f} µs, en büyük sapma {7:.0f} µs. {6}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="237" />
      <source>Bus {0}: {1}</source>
      <translation>Veri yolu {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="281" />
      <source>CCW</source>
      <translation>Saat yönü tersi</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="59" />
      <source>CCW (M04)</source>
      <translation>Sol (M04)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="189" />
      <source>CHAIN &amp; DOOR OPEN</source>
      <translation>DEVRE VE KAPI AÇIK</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="281" />
      <source>CW</source>
      <translation>Saat yönü</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="59" />
      <source>CW (M03)</source>
      <translation>Sağ (M03)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="263" />
      <source>Cancel</source>
      <translation>İptal</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="218" />
      <source>Cannot intersect parallel lines</source>
      <translation>paralel doğrular kesiştirilemez</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="279" />
      <source>Cannot run: {0}</source>
      <translation>Çalıştırılamaz: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>Cause</source>
      <translation>Neden</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="127" />
      <source>Change service password</source>
      <translation>Servis şifresini değiştir</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="213" />
      <source>Checking {0} …</source>
      <translation>{0} denetleniyor …</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="234" />
      <source>Checking {0} … {1} %</source>
      <translation>{0} denetleniyor … %{1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="38" />
      <source>Classic</source>
      <translation>Klasik</translation>
    </message>
    <message>
      <location filename="../../app/pages/preview.py" line="44" />
      <source>Clear</source>
      <translation>Temizle</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="81" />
      <source>Clear G92</source>
      <translation>G92'yi sil</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="114" />
      <source>Clearance</source>
      <translation>Emniyet mesafesi</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="105" />
      <source>Connect</source>
      <translation>Bağlan</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="111" />
      <source>Connect to the drives</source>
      <translation>Sürücülere bağlan</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="105" />
      <source>Connect to the drives and enable them?</source>
      <translation>Sürücülere bağlanılıp etkinleştirilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/widgets/jog_panel.py" line="40" />
      <source>Continuous</source>
      <translation>Sürekli</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="79" />
      <source>Coolant</source>
      <translation>Soğutma sıvısı</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="44" />
      <source>Coordinate systems</source>
      <translation>Koordinat sistemleri</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="219" />
      <source>Corner finish failed at ({0},{1})</source>
      <translation>({0},{1}) noktasında köşe bitirme başarısız</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="93" />
      <source>Corner tolerance (G64)</source>
      <translation>Köşe toleransı (G64)</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="99" />
      <source>Corner velocity step</source>
      <translation>Köşe hız sıçraması</translation>
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
      <location filename="../../app/pages/parameters.py" line="198" />
      <source>Current service password:</source>
      <translation>Mevcut servis şifresi:</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="34" />
      <source>Cycle start</source>
      <translation>Çevrim başlat</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="223" />
      <source>Cycle start refused: the program has errors (line {0})</source>
      <translation>Çevrim başlatma reddedildi: programda hata var (satır {0})</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="24" />
      <source>Cycle time</source>
      <translation>Çevrim süresi</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="88" />
      <source>Cycle time Ts</source>
      <translation>Çevrim süresi Ts</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="189" />
      <source>Cycle time {0}; limits Vmax {1:g} mm/s, Amax {2:g} mm/s², Jmax {3:g} mm/s³</source>
      <translation>Çevrim süresi {0}; sınırlar Vmax {1:g} mm/s, Amax {2:g} mm/s², Jmax {3:g} mm/s³</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="36" />
      <source>Cycle timing: start jitter histogram (µs)</source>
      <translation>Çevrim zamanlaması: başlangıç sapması histogramı (µs)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="220" />
      <source>D word with no G41, G41.1, G42, G42.1 or G96 to use it</source>
      <translation>D kelimesini kullanacak G41, G41.1, G42, G42.1 ya da G96 yok</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="191" />
      <source>DOOR OPEN</source>
      <translation>KAPI AÇIK</translation>
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
      <location filename="../../app/widgets/probing_panel.py" line="111" />
      <source>Depth below the start</source>
      <translation>Başlangıcın altındaki derinlik</translation>
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
      <location filename="../../app/widgets/probing_panel.py" line="109" />
      <source>Diameter as expected</source>
      <translation>Beklenen çap</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="110" />
      <source>Diameter tolerance</source>
      <translation>Çap toleransı</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="14" />
      <source>Direction</source>
      <translation>Yön</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="233" />
      <source>Discard</source>
      <translation>Vazgeç</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="103" />
      <source>Disconnect</source>
      <translation>Bağlantıyı kes</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="111" />
      <source>Disconnect the drives</source>
      <translation>Sürücülerin bağlantısını kes</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="19" />
      <source>Disconnected</source>
      <translation>Bağlı değil</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="112" />
      <source>Distance along the faces</source>
      <translation>Yüzler boyunca mesafe</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Drive</source>
      <translation>Sürücü</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="221" />
      <source>E word with no G33, G33.1, G76, M67 or M68 to use it</source>
      <translation>E kelimesini kullanacak G33, G33.1, G76, M67 ya da M68 yok</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="243" />
      <source>E-STOP</source>
      <translation>ACİL STOP</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="191" />
      <source>E-STOP CHAIN OPEN</source>
      <translation>ACİL STOP DEVRESİ AÇIK</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="26" />
      <source>E-stop</source>
      <translation>Acil stop</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="268" />
      <source>E-stop chain</source>
      <translation>Acil stop devresi</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="195" />
      <source>E-stop chain closed</source>
      <translation>Acil stop devresi kapalı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="96" />
      <source>E-stop chain open (the machine's safety circuit): quick stop of all axes; the drives cannot be enabled until it is closed again</source>
      <translation>Acil stop devresi açık (makinenin güvenlik devresi): tüm eksenler hızlı durduruldu; devre yeniden kapanana kadar sürücüler etkinleştirilemez</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="16" />
      <source>E-stop is not active</source>
      <translation>acil stop etkin değil</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="84" />
      <source>E-stop pressed</source>
      <translation>Acil stop basıldı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="86" />
      <source>E-stop pressed {0}</source>
      <translation>Acil stop basıldı {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="85" />
      <source>E-stop pressed: {0}</source>
      <translation>Acil stop basıldı: {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="83" />
      <source>E-stop: quick stop of all axes ({0})</source>
      <translation>Acil stop: tüm eksenler hızlı durduruldu ({0})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="166" />
      <source>E-stop: {0}</source>
      <translation>Acil stop: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="17" />
      <source>Edge</source>
      <translation>Kenar</translation>
    </message>
    <message>
      <location filename="../../app/widgets/keyboard.py" line="29" />
      <source>Enter</source>
      <translation>Giriş</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="71" />
      <source>EtherCAT</source>
      <translation>EtherCAT</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="39" />
      <source>EtherCAT (SOEM)</source>
      <translation>EtherCAT (SOEM)</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="38" />
      <source>Exact</source>
      <translation>Tam</translation>
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
      <location filename="../../app/message_text.py" line="222" />
      <source>F word with {0}: the feed is the pitch K times the spindle speed</source>
      <translation>{0} ile F kelimesi: ilerleme, K hatvesi çarpı iş mili hızıdır</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="16" />
      <source>FE window</source>
      <translation>Takip hatası penceresi</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="115" />
      <source>Fast probe feed</source>
      <translation>Hızlı prob ilerlemesi</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="501" />
      <source>Feed F{0:.0f} programmed, {1} now</source>
      <translation>İlerleme F{0:.0f} programlanan, şimdi {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="35" />
      <source>Feed hold</source>
      <translation>İlerleme durdur</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="138" />
      <source>Feed override</source>
      <translation>İlerleme oranı</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="54" />
      <source>File name in {0}:</source>
      <translation>{0} içinde dosya adı:</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="38" />
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
      <location filename="../../app/pages/manual.py" line="83" />
      <source>Flood (M08)</source>
      <translation>Bol sıvı (M08)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="299" />
      <source>Found (machine): {0} (only reported)</source>
      <translation>Bulunan (makine): {0} (yalnızca bildirildi)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="298" />
      <source>Found (machine): {0}; written to {1}</source>
      <translation>Bulunan (makine): {0}; {1} sistemine yazıldı</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="107" />
      <source>G-code block, e.g. G01 X10 F600</source>
      <translation>G-kodu bloğu, ör. G01 X10 F600</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="223" />
      <source>G04 needs a P word (dwell time in seconds)</source>
      <translation>G04 bir P kelimesi ister (saniye cinsinden bekleme süresi)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="224" />
      <source>G05 needs both I and J, or neither (then the first control point mirrors the last G05's P and Q)</source>
      <translation>G05 ya I ile J'nin ikisini de ister ya da hiçbirini (o zaman ilk kontrol noktası son G05'in P ve Q'sunun aynasıdır)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="225" />
      <source>G05 needs both P and Q (the second control point, from the end point)</source>
      <translation>G05 hem P hem Q ister (ikinci kontrol noktası, bitiş noktasından)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="226" />
      <source>G05.1 needs both I and J (the middle control point, from the start)</source>
      <translation>G05.1 hem I hem J ister (orta kontrol noktası, başlangıçtan)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="227" />
      <source>G05.2 needs both X and Y for a control point</source>
      <translation>G05.2 bir kontrol noktası için hem X hem Y ister</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="228" />
      <source>G05.3 without G05.2 before it: there is no NURBS to end</source>
      <translation>önünde G05.2 olmadan G05.3: bitirilecek NURBS yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="229" />
      <source>G10 L0 (reload the tool table) with tool {0} in the spindle: unload it first (M6 T0 or M61 Q0)</source>
      <translation>iş milinde {0} takımı varken G10 L0 (takım tablosunu yeniden yükle): önce onu çıkarın (M6 T0 ya da M61 Q0)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="230" />
      <source>G10 L2 R rotates the XY plane: this machine has no X and Y</source>
      <translation>G10 L2 R, XY düzlemini döndürür: bu makinede X ve Y yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="231" />
      <source>G10 L2/L20 needs P0-P9 (0: the system in use, 1: G54 ... 9: G59.3)</source>
      <translation>G10 L2/L20, P0-P9 ister (0: kullanılan sistem, 1: G54 ... 9: G59.3)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="232" />
      <source>G10 L{0} P{1}: tool T{2} is not in the tool table (add it on the Tools page first)</source>
      <translation>G10 L{0} P{1}: T{2} takımı takım tablosunda yok (önce Takımlar sayfasında ekleyin)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="233" />
      <source>G10 L{0} R{1}: the tool radius cannot be negative</source>
      <translation>G10 L{0} R{1}: takım yarıçapı negatif olamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="234" />
      <source>G10 L{0} is not a G10 this control knows (L0, L1, L2, L10, L11, L20)</source>
      <translation>G10 L{0} bu kontrolün bildiği bir G10 değil (L0, L1, L2, L10, L11, L20)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="235" />
      <source>G10 L{0} needs P with the tool number (1 or more)</source>
      <translation>G10 L{0}, takım numarasıyla bir P ister (1 ya da daha fazla)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="236" />
      <source>G10 needs an L word (L2 or L20: coordinate system; L1, L10, L11: tool table)</source>
      <translation>G10 bir L kelimesi ister (L2 ya da L20: koordinat sistemi; L1, L10, L11: takım tablosu)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="237" />
      <source>G15 polar coordinates</source>
      <translation>G15 kutupsal koordinatlar</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="238" />
      <source>G16 polar coordinates</source>
      <translation>G16 kutupsal koordinatlar</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="239" />
      <source>G17.1 selects the UV plane, of U and V axes this machine does not have</source>
      <translation>G17.1 UV düzlemini seçer; bu makinede U ve V eksenleri yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="240" />
      <source>G18.1 selects the WU plane, of U and W axes this machine does not have</source>
      <translation>G18.1 WU düzlemini seçer; bu makinede U ve W eksenleri yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="241" />
      <source>G19.1 selects the VW plane, of V and W axes this machine does not have</source>
      <translation>G19.1 VW düzlemini seçer; bu makinede V ve W eksenleri yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="242" />
      <source>G33.1 in G96: the tap's pitch needs a known speed; program G97 and S in rpm</source>
      <translation>G96'da G33.1: kılavuzun hatvesi bilinen bir hız ister; G97 ve dev/dak cinsinden S programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="243" />
      <source>G33.1 moves the linear axes only</source>
      <translation>G33.1 yalnızca doğrusal eksenleri hareket ettirir</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="244" />
      <source>G33.1: the pitch K{0} must be above 0</source>
      <translation>G33.1: K{0} hatvesi 0'dan büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="245" />
      <source>G33: the pitch K{0} must be above 0</source>
      <translation>G33: K{0} hatvesi 0'dan büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="18" />
      <source>G4 dwells between the moves of a program; a block without motion has nothing to wait for</source>
      <translation>G4 bir programın hareketleri arasında bekler; hareketsiz bir blokta beklenecek bir şey yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="246" />
      <source>G43.2 needs an H word or axis words (the offset to add)</source>
      <translation>G43.2 bir H kelimesi ya da eksen kelimeleri ister (eklenecek ofset)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="247" />
      <source>G53 cannot be used in incremental mode (G91)</source>
      <translation>G53 artımsal kipte (G91) kullanılamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="248" />
      <source>G53 needs G00 or G01</source>
      <translation>G53, G00 ya da G01 ister</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="249" />
      <source>G53 needs G00 or G01 with axis words</source>
      <translation>G53, eksen kelimeleriyle G00 ya da G01 ister</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="250" />
      <source>G68 coordinate rotation</source>
      <translation>G68 koordinat döndürme</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="251" />
      <source>G69 coordinate rotation</source>
      <translation>G69 koordinat döndürme</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="252" />
      <source>G76 needs I, J and K words (the thread's offset, first cut and depth): {0} missing</source>
      <translation>G76; I, J ve K kelimelerini ister (dişin ofseti, ilk kesme ve derinlik): {0} eksik</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="253" />
      <source>G76 needs a P word (the thread pitch, length per turn)</source>
      <translation>G76 bir P kelimesi ister (diş hatvesi, tur başına boy)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="254" />
      <source>G76 threads along Z and cuts in X: this machine has no {0} axis</source>
      <translation>G76 Z boyunca diş açar ve X'te keser: bu makinede {0} ekseni yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="255" />
      <source>G76: H{0} (spring passes) must be a whole number of 0 or more</source>
      <translation>G76: H{0} (boşa pasolar) 0 ya da daha büyük bir tam sayı olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="256" />
      <source>G76: H{0} makes more than {1} passes</source>
      <translation>G76: H{0}, {1} pasodan fazlasını yapar</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="257" />
      <source>G76: I (the thread's offset from the drive line) must not be 0</source>
      <translation>G76: I (dişin sürüş çizgisinden ofseti) 0 olmamalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="258" />
      <source>G76: J (the first cut's depth) must be greater than 0</source>
      <translation>G76: J (ilk kesmenin derinliği) 0'dan büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="259" />
      <source>G76: J{0} to K{1} (R{2}) makes more than {3} passes</source>
      <translation>G76: J{0}'dan K{1}'e (R{2}) {3} pasodan fazlasını yapar</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="260" />
      <source>G76: K (the full thread depth) must be greater than J</source>
      <translation>G76: K (tam diş derinliği) J'den büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="261" />
      <source>G76: L{0} (taper ends) must be a whole number of 0 or more</source>
      <translation>G76: L{0} (konik uçlar) 0 ya da daha büyük bir tam sayı olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="262" />
      <source>G76: the pitch P{0} must be above 0</source>
      <translation>G76: P{0} hatvesi 0'dan büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="263" />
      <source>G87 back boring: it needs an oriented spindle stop (M19), which this machine's spindle does not have</source>
      <translation>G87 geri delik işleme: yönlendirilmiş iş mili durdurması (M19) gerekir, bu makinenin iş milinde yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="264" />
      <source>G88 boring with a manual retract: the operator would jog the spindle out during a program stop; use G86 or G89</source>
      <translation>G88 elle geri çekmeli delik işleme: operatör program duruşunda iş milini elle çıkarırdı; G86 ya da G89 kullanın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="265" />
      <source>G90.1 (absolute arc centre) needs both {0} and {1}</source>
      <translation>G90.1 (mutlak yay merkezi) hem {0} hem {1} ister</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="120" />
      <source>G92 offset: off</source>
      <translation>G92 ofseti: kapalı</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="123" />
      <source>G92 offset: {0} (on: every work position is shifted by it)</source>
      <translation>G92 ofseti: {0} (açık: her iş konumu bu kadar kayar)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="266" />
      <source>G93 inverse time: every feed move needs its F word (1/F minutes)</source>
      <translation>G93 ters zaman: her ilerleme hareketi kendi F kelimesini ister (1/F dakika)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="267" />
      <source>G95 feed per revolution in G96: the speed would follow X, and this spindle has no speed output to follow it; program G97 and S in rpm</source>
      <translation>G96'da G95 devir başına ilerleme: hız X'i izlerdi ve bu iş milinin onu izleyecek hız çıkışı yok; G97 ve dev/dak cinsinden S programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="268" />
      <source>G95 feed per revolution needs a spindle speed: S is 0</source>
      <translation>G95 devir başına ilerleme bir iş mili hızı ister: S 0</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="269" />
      <source>G96 needs an S word (the surface speed)</source>
      <translation>G96 bir S kelimesi ister (yüzey hızı)</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="38" />
      <source>Go to line</source>
      <translation>Satıra git</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="270" />
      <source>H word with no G43, G43.2 or G76 to use it</source>
      <translation>H kelimesini kullanacak G43, G43.2 ya da G76 yok</translation>
    </message>
    <message>
      <location filename="../../app/widgets/handwheel_box.py" line="30" />
      <source>Handwheel</source>
      <translation>El çarkı</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="223" />
      <source>Held by feed override 0 %</source>
      <translation>İlerleme ayarı %0 ile bekliyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="46" />
      <source>Home</source>
      <translation>Referansla</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="59" />
      <source>Home all axes</source>
      <translation>Tüm eksenleri referansla</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="91" />
      <source>Home all axes? The axes may move.</source>
      <translation>Tüm eksenler referanslansın mı? Eksenler hareket edebilir.</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="86" />
      <source>Home axis</source>
      <translation>Ekseni referansla</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="87" />
      <source>Home axis {0}? The axis may move.</source>
      <translation>{0} ekseni referanslansın mı? Eksen hareket edebilir.</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="32" />
      <source>Homed</source>
      <translation>Referanslı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="117" />
      <source>Homing</source>
      <translation>Referanslama</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="115" />
      <source>Homing required before a program</source>
      <translation>Programdan önce referanslama gerekli</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="110" />
      <source>Homing: {0}; {1}.</source>
      <translation>Referanslama: {0}; {1}.</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="271" />
      <source>How did we get here?</source>
      <translation>Buraya nasıl gelindi? (bu kontrolün bir hatası: lütfen programı bildirin)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="19" />
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
      <location filename="../../app/message_text.py" line="19" />
      <source>Inside corner</source>
      <translation>İç köşe</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="112" />
      <source>Interpolation</source>
      <translation>İnterpolasyon</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="15" />
      <source>Jmax</source>
      <translation>Jmax</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="39" />
      <source>Jog</source>
      <translation>Elle hareket</translation>
    </message>
    <message>
      <location filename="../../app/widgets/jog_panel.py" line="65" />
      <source>Jog speed</source>
      <translation>Elle hareket hızı</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="112" />
      <source>Keyboard</source>
      <translation>Klavye</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="14" />
      <source>Kind</source>
      <translation>Tür</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="272" />
      <source>L (the NURBS order) must be a whole number, got L{0}</source>
      <translation>L (NURBS derecesi) bir tam sayı olmalı, L{0} verildi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="273" />
      <source>L word with no canned cycle, G05.2, G10, G76 or M66 to use it</source>
      <translation>L kelimesini kullanacak sabit çevrim, G05.2, G10, G76 ya da M66 yok</translation>
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
      <location filename="../../app/pages/auto.py" line="481" />
      <source>Line {0}   Progress {1:.0f} %
Remaining {2}   Path speed {3}</source>
      <translation>Satır {0}   Tamamlanan %{1:.0f}
Kalan {2}   Yol hızı {3}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="238" />
      <source>Line {0}: {1}</source>
      <translation>Satır {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/signals_view.py" line="15" />
      <source>LinuxCNC</source>
      <translation>LinuxCNC</translation>
    </message>
    <message>
      <location filename="../../app/widgets/handwheel_box.py" line="66" />
      <source>Live: a detent moves {0} by {1}</source>
      <translation>Etkin: bir kademe {0} eksenini {1} kadar hareket ettirir</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="39" />
      <source>Load into machine</source>
      <translation>Makineye yükle</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="130" />
      <source>Lock service level</source>
      <translation>Servis seviyesini kilitle</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="37" />
      <source>Look-ahead</source>
      <translation>İleriye bakış</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="274" />
      <source>L{0}: more than {1} repeats in one block</source>
      <translation>L{0}: bir blokta {1} tekrardan fazla</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="275" />
      <source>L{0}: the repeats of a cycle are a whole number of 1 or more</source>
      <translation>L{0}: bir çevrimin tekrarları 1 ya da daha büyük bir tam sayıdır</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="20" />
      <source>M0 pauses a running program; an MDI block has nothing to pause</source>
      <translation>M0 çalışan bir programı duraklatır; bir MDI bloğunun duraklatacağı bir şey yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="181" />
      <source>M06: the spindle stops for the tool change</source>
      <translation>M06: takım değişimi için iş mili durur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="21" />
      <source>M1 pauses a running program; an MDI block has nothing to pause</source>
      <translation>M1 çalışan bir programı duraklatır; bir MDI bloğunun duraklatacağı bir şey yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="276" />
      <source>M19 orients the spindle, which this machine's spindle cannot</source>
      <translation>M19 iş milini yönlendirir; bu makinenin iş mili bunu yapamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="277" />
      <source>M52 (adaptive feed) scales the feed by an input this machine does not have</source>
      <translation>M52 (uyarlamalı ilerleme) ilerlemeyi bu makinede olmayan bir girişle ölçekler</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="22" />
      <source>M6 runs in a program; in MDI put the tool in by hand and say which it is with M61 Q&lt;n&gt; (or on the Tools page)</source>
      <translation>M6 bir programda çalışır; MDI'da takımı elle takın ve hangisi olduğunu M61 Q&lt;n&gt; ile bildirin (ya da Takımlar sayfasında)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="278" />
      <source>M60 exchanges pallets and pauses; this machine has no pallet shuttle</source>
      <translation>M60 paletleri değiştirir ve duraklar; bu makinede palet değiştirici yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="279" />
      <source>M61 needs a Q word (the tool now in the spindle)</source>
      <translation>M61 bir Q kelimesi ister (şu an iş milindeki takım)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="23" />
      <source>M66 (line {0}): input P{1} is not on this machine ([[inputs]])</source>
      <translation>M66 ({0}. satır): P{1} girişi bu makinede yok ([[inputs]])</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="157" />
      <source>M66 (line {0}): input P{1} timed out after {2} s: #5399 = -1</source>
      <translation>M66 (satır {0}): P{1} girişi {2} s sonra zaman aşımına uğradı: #5399 = -1</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="25" />
      <source>M66 (line {0}): the drive of input P{1} does not send its digital inputs (0x60FD)</source>
      <translation>M66 ({0}. satır): P{1} girişinin sürücüsü dijital girişlerini göndermiyor (0x60FD)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="26" />
      <source>M66 (line {0}): the terminal of input P{1} is not on the bus</source>
      <translation>M66 (satır {0}): P{1} girişinin terminali veri yolunda değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="280" />
      <source>M66 E (an analog input): this machine has no analog inputs</source>
      <translation>M66 E (bir analog giriş): bu makinede analog giriş yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="281" />
      <source>M66 L{0}: the wait mode is 0 (now), 1 (rise), 2 (fall), 3 (high) or 4 (low)</source>
      <translation>M66 L{0}: bekleme kipi 0 (hemen), 1 (yükselen), 2 (düşen), 3 (yüksek) ya da 4 (düşük) olur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="282" />
      <source>M66 P{0}: no such digital input on this machine ({1})</source>
      <translation>M66 P{0}: bu makinede böyle bir dijital giriş yok ({1})</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="283" />
      <source>M66 needs a P word (the number of a digital input)</source>
      <translation>M66 bir P kelimesi ister (bir dijital girişin numarası)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="27" />
      <source>M66 reads an input for the program that follows it; an MDI block keeps no value for the next one (the Diagnostics page shows the inputs)</source>
      <translation>M66 kendisinden sonra gelen program için bir girişi okur; bir MDI bloğu bir sonrakine değer bırakmaz (girişleri Tanılama sayfası gösterir)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="284" />
      <source>M66: zero timeout with a wait mode other than immediate (give Q, seconds)</source>
      <translation>M66: hemen dışında bir bekleme kipiyle sıfır zaman aşımı (Q verin, saniye)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="285" />
      <source>M72: no modal state saved at this level (M70 or M73 first)</source>
      <translation>M72: bu düzeyde kaydedilmiş kip durumu yok (önce M70 ya da M73)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="286" />
      <source>M73 saves the state for the return of a subroutine: use M70 in the main program</source>
      <translation>M73 durumu bir alt programın dönüşü için kaydeder: ana programda M70 kullanın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="287" />
      <source>M98 L{0}: the runs of a subprogram are a whole number from 0 to 1e9</source>
      <translation>M98 L{0}: bir alt programın çalıştırma sayısı 0 ile 1e9 arasında bir tam sayıdır</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="288" />
      <source>M98 P{0}: a subprogram number is a whole number from 0 to 1e9</source>
      <translation>M98 P{0}: alt program numarası 0 ile 1e9 arasında bir tam sayıdır</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="289" />
      <source>M98 P{0}: no O{1} in this program</source>
      <translation>M98 P{0}: bu programda O{1} yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="290" />
      <source>M98 needs a P word (the number of the O subprogram to run)</source>
      <translation>M98 bir P kelimesi ister (çalıştırılacak O alt programının numarası)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="291" />
      <source>M98 takes only P and L words, not {0}</source>
      <translation>M98 yalnızca P ve L kelimelerini alır, {0} almaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="292" />
      <source>M99 inside an O-word subroutine: it ends with its endsub or return</source>
      <translation>O-kelimesi alt programı içinde M99: o, kendi endsub ya da return'üyle biter</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="102" />
      <source>MDI</source>
      <translation>MDI</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="28" />
      <source>MDI takes one block (one line)</source>
      <translation>MDI bir blok alır (bir satır)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/tracking_view.py" line="104" />
      <source>MSE</source>
      <translation>MSE</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="118" />
      <source>Machine</source>
      <translation>Makine</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="32" />
      <source>Machine position</source>
      <translation>Makine konumu</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="28" />
      <source>Machine zero</source>
      <translation>Makine sıfırı</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="96" />
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
      <location filename="../../app/pages/manual.py" line="84" />
      <source>Mist (M07)</source>
      <translation>Sis (M07)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="293" />
      <source>M{0} and M{1} are in the same modal group (one per block)</source>
      <translation>M{0} ve M{1} aynı kip grubunda (blok başına bir tane)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="294" />
      <source>M{0} is a user M-code this machine does not define (add it to [[mcodes]] in the machine configuration: a pause with a message, an output or nothing)</source>
      <translation>M{0} bu makinenin tanımlamadığı bir kullanıcı M kodu (makine yapılandırmasında [[mcodes]] altına ekleyin: mesajlı bir duraklama, bir çıkış ya da hiçbir şey)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="295" />
      <source>M{0} needs P with a configured output number ({1})</source>
      <translation>M{0}, yapılandırılmış bir çıkış numarasıyla P ister ({1})</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="296" />
      <source>M{0} needs an E word, the analog output's number (0 or more)</source>
      <translation>M{0} bir E kelimesi ister, analog çıkışın numarası (0 ya da daha fazla)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="297" />
      <source>N word (line number) must begin the block</source>
      <translation>N kelimesi (satır numarası) bloğun başında olmalı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="188" />
      <source>Network adapter</source>
      <translation>Ağ bağdaştırıcısı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="189" />
      <source>Network interface of the EtherCAT bus:</source>
      <translation>EtherCAT veri yolunun ağ arayüzü:</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="37" />
      <source>New</source>
      <translation>Yeni</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="201" />
      <source>New service password (at least {0} characters):</source>
      <translation>Yeni servis şifresi (en az {0} karakter):</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="133" />
      <source>New tool number</source>
      <translation>Yeni takım numarası</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="74" />
      <source>No</source>
      <translation>Hayır</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="330" />
      <source>No moves to draw</source>
      <translation>Çizilecek hareket yok</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="77" />
      <source>No program loaded.</source>
      <translation>Yüklü program yok.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/signals_view.py" line="44" />
      <source>No signal is wired ([signals] in the machine configuration).</source>
      <translation>Bağlı sinyal yok (makine yapılandırmasında [signals]).</translation>
    </message>
    <message>
      <location filename="../../app/widgets/spindle_view.py" line="106" />
      <source>No spindle drive: the spindle is switched by output bits; no speed is read</source>
      <translation>İş mili sürücüsü yok: iş mili çıkış bitleriyle açılıp kapanır; hız okunmaz</translation>
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
      <location filename="../../app/widgets/handwheel_box.py" line="69" />
      <source>Not live: {0}</source>
      <translation>Etkin değil: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="298" />
      <source>Not monotonic</source>
      <translation>monoton değil (bu kontrolün bir hatası: lütfen programı bildirin)</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="212" />
      <source>Nothing changed: {0}</source>
      <translation>Hiçbir şey değişmedi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/signals_view.py" line="15" />
      <source>Now</source>
      <translation>Şimdi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="299" />
      <source>O-word program numbers must be alone on their line</source>
      <translation>O-kelimesi program numaraları kendi satırlarında tek başına olmalı</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="83" />
      <source>OK</source>
      <translation>Tamam</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="266" />
      <source>OPC UA</source>
      <translation>OPC UA</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="120" />
      <source>OPC UA server: not serving: {0}</source>
      <translation>OPC UA sunucusu: hizmet vermiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="118" />
      <source>OPC UA server: off ([opcua] enabled = false)</source>
      <translation>OPC UA sunucusu: kapalı ([opcua] enabled = false)</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="128" />
      <source>OPC UA server: serving {0} ({1}), certificate SHA-1 {2}</source>
      <translation>OPC UA sunucusu: {0} adresinde hizmet veriyor ({1}), sertifika SHA-1 {2}</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="124" />
      <source>OPC UA server: serving {0} with security None: anyone who reaches the port reads the machine</source>
      <translation>OPC UA sunucusu: {0} adresinde güvenliksiz (None) hizmet veriyor: bağlantı noktasına ulaşan herkes makineyi okuyabilir</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="122" />
      <source>OPC UA server: starting at {0}</source>
      <translation>OPC UA sunucusu: {0} adresinde başlıyor</translation>
    </message>
    <message>
      <location filename="../../app/widgets/handwheel_box.py" line="34" />
      <source>Off</source>
      <translation>Kapalı</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="59" />
      <source>Off (M05)</source>
      <translation>Kapalı (M05)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/handwheel_box.py" line="71" />
      <source>Off: choose an axis ({0} a detent)</source>
      <translation>Kapalı: bir eksen seçin (kademe başına {0})</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="144" />
      <source>Only report</source>
      <translation>Yalnızca bildir</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="64" />
      <source>Open file</source>
      <translation>Dosya aç</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="64" />
      <source>Open program</source>
      <translation>Program aç</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="37" />
      <source>Open…</source>
      <translation>Aç…</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="122" />
      <source>Optional stop</source>
      <translation>İsteğe bağlı duruş</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="24" />
      <source>Optional stop (M1)</source>
      <translation>İsteğe bağlı duruş (M1)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="258" />
      <source>Or start it again from line 1, from where the tool stands now.</source>
      <translation>Ya da programı takımın şu anki yerinden, 1. satırdan yeniden başlatın.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/keypad.py" line="99" />
      <source>Out of range: {0} to {1}</source>
      <translation>Aralık dışında: {0} ile {1} arası</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="29" />
      <source>Outside corner</source>
      <translation>Dış köşe</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="300" />
      <source>P (number of turns) must be a whole number &gt;= 1, got P{0}</source>
      <translation>P (tur sayısı) &gt;= 1 bir tam sayı olmalı, P{0} verildi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="301" />
      <source>P word with no G code that uses it (G04, G02/G03, G05, G05.2, G64, G82, G84, G86, G89)</source>
      <translation>P kelimesini kullanan G kodu yok (G04, G02/G03, G05, G05.2, G64, G82, G84, G86, G89)</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="37" />
      <source>Paper (per block)</source>
      <translation>Makaledeki (blok başına)</translation>
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
      <location filename="../../app/pages/diagnostics.py" line="71" />
      <source>Path v / a / j</source>
      <translation>Yol v / a / j</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="161" />
      <source>Planned when this page is shown.</source>
      <translation>Bu sayfa gösterildiğinde planlanır.</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="107" />
      <source>Planner mode</source>
      <translation>Planlayıcı kipi</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="168" />
      <source>Planning…</source>
      <translation>Planlanıyor…</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="29" />
      <source>Pocket</source>
      <translation>Cep</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="30" />
      <source>Points apart along the face</source>
      <translation>Yüz boyunca noktalar arası</translation>
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
      <location filename="../../app/pages/part_zero.py" line="49" />
      <source>Probe</source>
      <translation>Prob</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="101" />
      <source>Probe input: free</source>
      <translation>Prob girişi: serbest</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="102" />
      <source>Probe input: none ([probe] drive in the machine configuration)</source>
      <translation>Prob girişi: yok (makine yapılandırmasında [probe] drive)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="101" />
      <source>Probe input: touching</source>
      <translation>Prob girişi: temas ediyor</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="257" />
      <source>Probing starts with the machine idle.</source>
      <translation>Problama makine boştayken başlar.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="11" />
      <source>Product</source>
      <translation>Ürün</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="72" />
      <source>Production</source>
      <translation>Üretim</translation>
    </message>
    <message>
      <location filename="../../app/pages/__init__.py" line="26" />
      <source>Program</source>
      <translation>Program</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="429" />
      <source>Program finished in {0}</source>
      <translation>Program {0} sürede bitti</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="249" />
      <source>Program loaded: {0}</source>
      <translation>Program yüklendi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="245" />
      <source>Program loaded: {0}; G64: {1} corners smoothed, at most {2:.3f} mm from the programmed path</source>
      <translation>Program yüklendi: {0}; G64: {1} köşe yumuşatıldı, programlanan yoldan en çok {2:.3f} mm</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="262" />
      <source>Program refused: {0} error(s)</source>
      <translation>Program reddedildi: {0} hata</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="23" />
      <source>Program stop (M0)</source>
      <translation>Program duruşu (M0)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="434" />
      <source>Program stopped at line {0}: {1}</source>
      <translation>Program {0}. satırda durdu: {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="302" />
      <source>P{0}: more than {1} turns</source>
      <translation>P{0}: {1} turdan fazla</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="303" />
      <source>Q word with no code that uses it (G05, G64, M61, G73, G76, G83, M66, M67, M68)</source>
      <translation>Q kelimesini kullanan kod yok (G05, G64, M61, G73, G76, G83, M66, M67, M68)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="304" />
      <source>R ({0}) below the bottom {1} ({2}) of the canned cycle in {3}</source>
      <translation>R ({0}), {3} içindeki sabit çevrimin {1} tabanının ({2}) altında</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="305" />
      <source>R not allowed in G10 L20 (the rotation is set with G10 L2 R)</source>
      <translation>G10 L20'de R kullanılamaz (döndürme G10 L2 R ile ayarlanır)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="243" />
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
      <location filename="../../app/pages/auto.py" line="141" />
      <source>Rapid override</source>
      <translation>Hızlı hareket oranı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="31" />
      <source>Rapid speed</source>
      <translation>Hızlı hareket hızı</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="290" />
      <source>Recover</source>
      <translation>Geri yükle</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="357" />
      <source>Refused: {0}</source>
      <translation>Reddedildi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="167" />
      <source>Release E-stop</source>
      <translation>Acil stopu bırak</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="168" />
      <source>Release the emergency stop and enable the drives?</source>
      <translation>Acil stop bırakılıp sürücüler etkinleştirilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="82" />
      <source>Reload</source>
      <translation>Yeniden yükle</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="205" />
      <source>Repeat the new password:</source>
      <translation>Yeni şifreyi tekrarlayın:</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="212" />
      <source>Replace the whole tool table by {0}?</source>
      <translation>Tüm takım tablosu {0} ile değiştirilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="46" />
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
      <location filename="../../app/pages/auto.py" line="262" />
      <source>Resume at line {0}</source>
      <translation>{0}. satırdan devam et</translation>
    </message>
    <message>
      <location filename="../../app/widgets/apply_bar.py" line="22" />
      <source>Revert</source>
      <translation>Geri al</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="309" />
      <source>Run from line</source>
      <translation>Satırdan çalıştır</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="314" />
      <source>Run from line refused: {0}</source>
      <translation>Satırdan çalıştırma reddedildi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="524" />
      <source>Run from line: {0}</source>
      <translation>Satırdan çalıştır: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="128" />
      <source>Run from line…</source>
      <translation>Satırdan çalıştır…</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="120" />
      <source>Run log exported</source>
      <translation>Çalışma kaydı dışa aktarıldı</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="164" />
      <source>Run the probing</source>
      <translation>Problamayı çalıştır</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="239" />
      <source>Run the program anyway?</source>
      <translation>Program yine de çalıştırılsın mı?</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="320" />
      <source>Run the program from line {0}?</source>
      <translation>Program {0}. satırdan çalıştırılsın mı?</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="20" />
      <source>Running</source>
      <translation>Çalışıyor</translation>
    </message>
    <message>
      <location filename="../../app/widgets/tracking_view.py" line="112" />
      <source>Samples: {0}</source>
      <translation>Örnek sayısı: {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="37" />
      <source>Save</source>
      <translation>Kaydet</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="37" />
      <source>Save as…</source>
      <translation>Farklı kaydet…</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="338" />
      <source>Save failed</source>
      <translation>Kaydetme başarısız</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="54" />
      <source>Save program as</source>
      <translation>Programı farklı kaydet</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="306" />
      <source>Save with errors?</source>
      <translation>Hatalarla kaydedilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="113" />
      <source>Search distance</source>
      <translation>Arama mesafesi</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="109" />
      <source>Send</source>
      <translation>Gönder</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="134" />
      <source>Service</source>
      <translation>Servis</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="294" />
      <source>Service level</source>
      <translation>Servis seviyesi</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="323" />
      <source>Service level locked after {0} minutes without input</source>
      <translation>Servis seviyesi {0} dakika işlem yapılmadığı için kilitlendi</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="299" />
      <source>Service level refused: {0}</source>
      <translation>Servis seviyesi reddedildi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="301" />
      <source>Service level unlocked</source>
      <translation>Servis seviyesi açıldı</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="198" />
      <source>Service password</source>
      <translation>Servis şifresi</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="294" />
      <source>Service password:</source>
      <translation>Servis şifresi:</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="48" />
      <source>Set here as zero</source>
      <translation>Burayı sıfır yap</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="95" />
      <source>Set machine zero</source>
      <translation>Makine sıfırını ayarla</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>Severity</source>
      <translation>Önem</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="40" />
      <source>Show history</source>
      <translation>Geçmişi göster</translation>
    </message>
    <message>
      <location filename="../../app/pages/preview.py" line="40" />
      <source>Show in program</source>
      <translation>Programda göster</translation>
    </message>
    <message>
      <location filename="../../app/widgets/signals_view.py" line="15" />
      <source>Signal</source>
      <translation>Sinyal</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="72" />
      <source>Signals</source>
      <translation>Sinyaller</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="39" />
      <source>Simulated</source>
      <translation>Benzetim</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="118" />
      <source>Single block</source>
      <translation>Tek blok</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="116" />
      <source>Slow probe feed</source>
      <translation>Yavaş prob ilerlemesi</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>Source</source>
      <translation>Kaynak</translation>
    </message>
    <message>
      <location filename="../../app/widgets/keyboard.py" line="29" />
      <source>Space</source>
      <translation>Boşluk</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="72" />
      <source>Spindle</source>
      <translation>İş mili</translation>
    </message>
    <message>
      <location filename="../../app/widgets/spindle_view.py" line="110" />
      <source>Spindle drive: no speed read yet</source>
      <translation>İş mili sürücüsü: henüz hız okunmadı</translation>
    </message>
    <message>
      <location filename="../../app/widgets/spindle_view.py" line="117" />
      <source>Spindle drive: {0} rpm commanded, {1} rpm read: {2}</source>
      <translation>İş mili sürücüsü: {0} dev/dak istendi, {1} dev/dak okundu: {2}</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="497" />
      <source>Spindle off</source>
      <translation>İş mili durdu</translation>
    </message>
    <message>
      <location filename="../../app/widgets/spindle_view.py" line="101" />
      <source>Spindle on a VFD (analog output {0}): {1} rpm commanded, {2} V sent; no speed is read</source>
      <translation>İş mili bir frekans çeviricide (analog çıkış {0}): {1} dev/dak istendi, {2} V gönderildi; hız okunmuyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="144" />
      <source>Spindle override</source>
      <translation>İş mili oranı</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="66" />
      <source>Spindle speed</source>
      <translation>İş mili devri</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="498" />
      <source>Spindle {0} {1:.0f} rpm</source>
      <translation>İş mili {0} {1:.0f} dev/dk</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="175" />
      <source>Spindle: {0}, {1:.0f} rpm</source>
      <translation>İş mili: {0}, {1:.0f} dev/dak</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="24" />
      <source>Start</source>
      <translation>Başlangıç</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="249" />
      <source>Start from the beginning</source>
      <translation>Baştan başlat</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="23" />
      <source>State</source>
      <translation>Durum</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="36" />
      <source>Stop</source>
      <translation>Dur</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="103" />
      <source>Stop and disable the drives?</source>
      <translation>Sürücüler durdurulup devre dışı bırakılsın mı?</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="24" />
      <source>Stopping</source>
      <translation>Duruyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="31" />
      <source>S{0} is over the spindle's maximum of {1} rpm ([controller] spindle_max_rpm)</source>
      <translation>S{0}, iş milinin en yüksek {1} dev/dak hızının üstünde ([controller] spindle_max_rpm)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="32" />
      <source>T selects the tool for a program's M6; in MDI say which tool is in the spindle with M61 Q&lt;n&gt;</source>
      <translation>T bir programın M6'sı için takımı seçer; MDI'da iş milindeki takımı M61 Q&lt;n&gt; ile bildirin</translation>
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
      <location filename="../../app/pages/part_zero.py" line="72" />
      <source>Tap a value to type it. Touch off: the current position becomes the work coordinate you enter, in the selected offset.</source>
      <translation>Yazmak için bir değere dokunun. Dokunarak sıfırlama: şu anki konum, seçili ofsette girdiğiniz iş koordinatı olur.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="42" />
      <source>Target…</source>
      <translation>Hedef…</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="38" />
      <source>Taylor</source>
      <translation>Taylor</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="200" />
      <source>The control did not shut down cleanly: home the axes (Machine zero, Home all) before running a program</source>
      <translation>Kontrol düzgün kapanmadı: program çalıştırmadan önce eksenleri referanslayın (Makine sıfırı, Tüm eksenleri referansla)</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="190" />
      <source>The control stopped without shutting down (power loss or killed), and this machine has no reference switches: where the axes stand is not known. Set machine zero, touch off the part zero again, then run the program from its start</source>
      <translation>Kontrol kapatılmadan durdu (elektrik kesintisi ya da sonlandırıldı) ve bu makinede referans anahtarı yok: eksenlerin nerede durduğu bilinmiyor. Makine sıfırını ayarlayın, parça sıfırını yeniden dokunarak alın, sonra programı baştan çalıştırın</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="277" />
      <source>The machine goes there the way drawn</source>
      <translation>Makine oraya çizilen yoldan gider</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="274" />
      <source>The machine goes up to Z{0:.3f} (machine), across, then down to it the way drawn</source>
      <translation>Makine Z{0:.3f} (makine) yüksekliğine çıkar, yatay gider, sonra çizilen yoldan oraya iner</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="90" />
      <source>The machine is moving.</source>
      <translation>Makine hareket ediyor.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/signals_view.py" line="42" />
      <source>The machine's signals as the drives and terminals report them ([signals] in the machine configuration). Marked: not what a machine at rest reads.</source>
      <translation>Sürücülerin ve terminallerin bildirdiği makine sinyalleri (makine yapılandırmasında [signals]). İşaretli: durağan bir makinenin okuduğu değer değil.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="283" />
      <source>The moves drawn run when you press Run; the result goes to {0}.</source>
      <translation>Çizilen hareketler Çalıştır'a basınca yapılır; sonuç {0} sistemine yazılır.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="284" />
      <source>The moves drawn run when you press Run; the result is only reported.</source>
      <translation>Çizilen hareketler Çalıştır'a basınca yapılır; sonuç yalnızca bildirilir.</translation>
    </message>
    <message>
      <location filename="../../app/widgets/handwheel_box.py" line="73" />
      <source>The pendant's selector chooses the axis and the step.</source>
      <translation>Ekseni ve adımı el kumandasının seçicisi belirler.</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="33" />
      <source>The probe moves toward the face (the second point is along it):</source>
      <translation>Prob yüze doğru hareket eder (ikinci nokta yüz boyunca):</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="34" />
      <source>The probe moves toward the face:</source>
      <translation>Prob yüze doğru hareket eder:</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="256" />
      <source>The program stopped at line {0} ({1}).</source>
      <translation>Program {0}. satırda durdu ({1}).</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="251" />
      <source>The program stopped at line {0} and cannot resume there: {1}</source>
      <translation>Program {0}. satırda durdu ve oradan devam edemez: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/parameters.py" line="210" />
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
      <location filename="../../app/widgets/dro.py" line="118" />
      <source>To go</source>
      <translation>Kalan</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="29" />
      <source>Tool</source>
      <translation>Takım</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="24" />
      <source>Tool change</source>
      <translation>Takım değişimi</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="500" />
      <source>Tool {0}</source>
      <translation>Takım {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="249" />
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
      <location filename="../../app/pages/part_zero.py" line="90" />
      <source>Touch off {0}</source>
      <translation>{0} dokunarak sıfırla</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="181" />
      <source>Touch off {0}: work Z of the surface the tip touches</source>
      <translation>{0} dokunarak ölç: ucun değdiği yüzeyin iş Z'si</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="154" />
      <source>Touch off {0}: work coordinate here</source>
      <translation>{0} dokunarak sıfırla: buradaki iş koordinatı</translation>
    </message>
    <message>
      <location filename="../../app/pages/diagnostics.py" line="71" />
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
      <location filename="../../app/message_text.py" line="35" />
      <source>T{0} has no tip diameter in the tool table: the edges found would be off by the ball's radius</source>
      <translation>T{0} için takım tablosunda uç çapı yok: bulunan kenarlar bilyenin yarıçapı kadar kayık olurdu</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="138" />
      <source>T{0} is already in the table.</source>
      <translation>T{0} tabloda zaten var.</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="36" />
      <source>T{0} is in the spindle, not the probe T{1}: a probing move would feed it into the part; put the probe in and say so (In the spindle, or M61 Q{2})</source>
      <translation>iş milinde T{0} var, prob T{1} değil: prob hareketi onu parçaya sürer; probu takın ve bildirin (İş milinde ya da M61 Q{2})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="73" />
      <source>T{0} is in the spindle: set another tool first</source>
      <translation>T{0} iş milinde: önce başka bir takım seçin</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="159" />
      <source>T{0} is not in the spindle: put it in and set it (In the spindle) first</source>
      <translation>T{0} iş milinde değil: önce takın ve ayarlayın (İş milinde)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="72" />
      <source>T{0} is not in the tool table</source>
      <translation>T{0} takım tablosunda yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="178" />
      <source>T{0} length {1} mm is longer than the Z travel ({2} mm): check the value and the surface it was touched off on</source>
      <translation>T{0} boyu {1} mm, Z hareket aralığından ({2} mm) uzun: değeri ve dokundurulduğu yüzeyi kontrol edin</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="158" />
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
      <location filename="../../app/message_text.py" line="41" />
      <source>T{0}: the measurement has no second contact</source>
      <translation>T{0}: ölçümde ikinci temas yok</translation>
    </message>
    <message>
      <location filename="../../app/widgets/service_gate.py" line="31" />
      <source>Unlock</source>
      <translation>Kilidi aç</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="231" />
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
      <location filename="../../app/message_text.py" line="42" />
      <source>Where the part is from the probe:</source>
      <translation>Parçanın probdan göre yeri:</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="43" />
      <source>Where the walls are from the probe:</source>
      <translation>Duvarların probdan göre yeri:</translation>
    </message>
    <message>
      <location filename="../../app/widgets/signals_view.py" line="15" />
      <source>Wired to</source>
      <translation>Bağlı olduğu yer</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="63" />
      <source>Work</source>
      <translation>İş</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="44" />
      <source>Work = tool tip in {0}</source>
      <translation>İş = takım ucu, {0}</translation>
    </message>
    <message>
      <location filename="../../app/pages/preview.py" line="97" />
      <source>Work coordinates ({0}): the cross is the work zero, the dashed box the machine's travel.</source>
      <translation>İş koordinatları ({0}): artı işareti iş sıfırı, kesikli kutu makinenin hareket alanı.</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="85" />
      <source>Work light</source>
      <translation>Çalışma lambası</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="136" />
      <source>Write the result to:</source>
      <translation>Sonucu şuraya yaz:</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="117" />
      <source>X reads after</source>
      <translation>Sonra X okunur</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="133" />
      <source>XY rotation (°)</source>
      <translation>XY dönüşü (°)</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="126" />
      <source>XY rotation of {0}: {1} degrees</source>
      <translation>{0} XY döndürmesi: {1} derece</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="37" />
      <source>XY turned {0:g}°</source>
      <translation>XY {0:g}° döndürülmüş</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="118" />
      <source>Y reads after</source>
      <translation>Sonra Y okunur</translation>
    </message>
    <message>
      <location filename="../../app/dialogs.py" line="73" />
      <source>Yes</source>
      <translation>Evet</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="119" />
      <source>Z reads after</source>
      <translation>Sonra Z okunur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="44" />
      <source>Z surface</source>
      <translation>Z yüzeyi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="306" />
      <source>a G-code program</source>
      <translation>G kodu programı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="307" />
      <source>a NURBS of order L = {0} needs at least {1} control points, the start included; it has {2}</source>
      <translation>L = {0} dereceli bir NURBS, başlangıç dahil en az {1} kontrol noktası ister; {2} tane var</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="45" />
      <source>a bore</source>
      <translation>bir delik</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="46" />
      <source>a boss</source>
      <translation>bir çıkıntı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="47" />
      <source>a gantry's second side: its home switch</source>
      <translation>gantrinin ikinci tarafı: referans anahtarı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="48" />
      <source>a gantry's second side: its negative limit switch</source>
      <translation>gantrinin ikinci tarafı: negatif limit anahtarı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="49" />
      <source>a gantry's second side: its positive limit switch</source>
      <translation>gantrinin ikinci tarafı: pozitif limit anahtarı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="118" />
      <source>a gantry's side homes only together with its other side</source>
      <translation>bir gantri tarafı yalnızca diğer tarafıyla birlikte referanslanır</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="110" />
      <source>a limit switch tripped</source>
      <translation>bir sınır anahtarı tetiklendi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="50" />
      <source>a load holds the spindle at 0-{0} rpm, got {1}</source>
      <translation>bir yük iş milini 0-{0} dev/dak arasında tutar, {1} verildi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="308" />
      <source>a machine configuration</source>
      <translation>makine yapılandırması</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="154" />
      <source>a probe move ended without the probe armed: the program stops here</source>
      <translation>bir prob hareketi prob kurulmadan bitti: program burada durur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="309" />
      <source>a program</source>
      <translation>program</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="310" />
      <source>a script of operator actions</source>
      <translation>operatör eylemleri betiği</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="311" />
      <source>a tool table</source>
      <translation>takım tablosu</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="312" />
      <source>a weight P without X and Y only on the block that begins the NURBS</source>
      <translation>X ve Y'siz bir P ağırlığı yalnızca NURBS'ü başlatan blokta olur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="313" />
      <source>a zero-degree inside corner cannot be cut with cutter compensation</source>
      <translation>sıfır derecelik bir iç köşe kesici telafisiyle kesilemez</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="58" />
      <source>acknowledge the active alarms first</source>
      <translation>önce etkin alarmları onaylayın</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="92" />
      <source>acknowledged</source>
      <translation>onaylandı</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="92" />
      <source>active</source>
      <translation>etkin</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="269" />
      <source>air</source>
      <translation>hava</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="53" />
      <source>air pressure present</source>
      <translation>hava basıncı var</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="77" />
      <source>alarm</source>
      <translation>alarm</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="54" />
      <source>already connected (machine is {0})</source>
      <translation>zaten bağlı (makine {0} durumunda)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="55" />
      <source>an edge</source>
      <translation>bir kenar</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="56" />
      <source>an inside corner</source>
      <translation>bir iç köşe</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="57" />
      <source>an outside corner</source>
      <translation>bir dış köşe</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="297" />
      <source>angle</source>
      <translation>açı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="65" />
      <source>another tool is in the spindle since it was loaded</source>
      <translation>program yüklendiğinden beri iş milinde başka bir takım var</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="314" />
      <source>approach feed must be a positive number, got {0}</source>
      <translation>yaklaşma ilerlemesi pozitif bir sayı olmalı, {0} verildi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="30" />
      <source>approach move: soft limit: {0}</source>
      <translation>yaklaşma hareketi: yazılım sınırı: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="59" />
      <source>approach move: {0}</source>
      <translation>yaklaşma hareketi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="169" />
      <source>arc extreme</source>
      <translation>yayın uç noktası</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="315" />
      <source>arc in plane {0} ({1}) needs axes {2} and {3}; this machine has {4}</source>
      <translation>{0} düzlemindeki yay ({1}) {2} ve {3} eksenlerini ister; bu makinede {4} var</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="316" />
      <source>arc move in a concave corner cannot be reached by the tool without gouging</source>
      <translation>içbükey köşedeki yay hareketine takım oyuk açmadan ulaşamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="317" />
      <source>arc move in a concave corner cannot be reached by the tool without gouging (the tool is too big for this corner)</source>
      <translation>içbükey köşedeki yay hareketine takım oyuk açmadan ulaşamaz (takım bu köşe için fazla büyük)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="318" />
      <source>arc needs R or a centre: R, I, J and K words all missing</source>
      <translation>yay R ya da bir merkez ister: R, I, J ve K kelimelerinin hepsi eksik</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="319" />
      <source>arc to arc motion is invalid because the arcs have the same centre</source>
      <translation>yaydan yaya hareket geçersiz, çünkü yayların merkezi aynı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="320" />
      <source>arc to arc motion makes a corner the compensated tool cannot fit in without gouging</source>
      <translation>yaydan yaya hareket, telafili takımın oyuk açmadan sığamayacağı bir köşe yapar</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="321" />
      <source>arc to straight motion makes a corner the compensated tool cannot fit in without gouging</source>
      <translation>yaydan doğruya hareket, telafili takımın oyuk açmadan sığamayacağı bir köşe yapar</translation>
    </message>
    <message>
      <location filename="../../app/widgets/spindle_view.py" line="116" />
      <source>at speed</source>
      <translation>hızında</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="60" />
      <source>at the switch</source>
      <translation>anahtarda</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="93" />
      <source>axes are not homed any more: home them before running a program</source>
      <translation>eksenler artık referanslı değil: program çalıştırmadan önce referanslayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="61" />
      <source>axes changed: reconnect the bus to apply</source>
      <translation>eksenler değişti: uygulamak için veri yolunu yeniden bağlayın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="56" />
      <source>axes not homed</source>
      <translation>eksenler referanslanmadı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="63" />
      <source>axes not homed: home them before probing</source>
      <translation>eksenler referanslanmadı: problamadan önce referanslayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="64" />
      <source>axes not homed: the machine Z is not known</source>
      <translation>eksenler referanslanmadı: makine Z'si bilinmiyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="65" />
      <source>axes not homed: the setter's position is not known</source>
      <translation>eksenler referanslanmadı: ayarlayıcının konumu bilinmiyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="55" />
      <source>axes not homed: {0} (home them or set machine zero first)</source>
      <translation>eksenler referanslanmadı: {0} (önce referanslayın ya da makine sıfırını ayarlayın)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="67" />
      <source>axes {0} report another position than saved: homed state cleared, home again</source>
      <translation>{0} eksenleri kaydedilenden başka bir konum bildiriyor: referans durumu silindi, yeniden referanslayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="322" />
      <source>axis words without a motion mode: program G00/G01/G02/G03 first</source>
      <translation>hareket kipi olmadan eksen kelimeleri: önce G00/G01/G02/G03 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="91" />
      <source>axis {0} did not reach OPERATION ENABLED within {1} s (drive state {2})</source>
      <translation>{0} ekseni {1} s içinde OPERATION ENABLED durumuna geçmedi (sürücü durumu {2})</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="68" />
      <source>axis {0} is at its soft limit {1}</source>
      <translation>{0} ekseni {1} yazılım sınırında</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="69" />
      <source>axis {0} is not homed: home it first</source>
      <translation>{0} ekseni referanslanmadı: önce referanslayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="323" />
      <source>axis {0} is not on this machine (axes: {1})</source>
      <translation>{0} ekseni bu makinede yok (eksenler: {1})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="107" />
      <source>axis {0} is on its negative limit switch: it may only jog away from it ({1})</source>
      <translation>{0} ekseni negatif sınır anahtarında: yalnızca ondan uzağa hareket ettirilebilir ({1})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="106" />
      <source>axis {0} is on its positive limit switch: it may only jog away from it ({1})</source>
      <translation>{0} ekseni pozitif sınır anahtarında: yalnızca ondan uzağa hareket ettirilebilir ({1})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="100" />
      <source>axis {0} on its negative limit switch: quick stop of all axes; override limits to jog it off the switch (toward +)</source>
      <translation>{0} ekseni negatif sınır anahtarında: tüm eksenler hızlı durduruldu; anahtardan çıkarmak için sınırları geçersiz kılın (+ yönüne)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="98" />
      <source>axis {0} on its positive limit switch: quick stop of all axes; override limits to jog it off the switch (toward -)</source>
      <translation>{0} ekseni pozitif sınır anahtarında: tüm eksenler hızlı durduruldu; anahtardan çıkarmak için sınırları geçersiz kılın (- yönüne)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="168" />
      <source>axis {0} reaches {1} ({2}), beyond its soft limit {3} {4}</source>
      <translation>{0} ekseni {1} değerine ulaşıyor ({2}), yazılım sınırının ötesinde: {3} {4}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="70" />
      <source>axis {0} stands outside its soft limits [{1}, {2}]</source>
      <translation>{0} ekseni yazılım sınırlarının [{1}, {2}] dışında duruyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="71" />
      <source>axis {0} would reach {1}, beyond its soft limit [{2}, {3}]</source>
      <translation>{0} ekseni {1} konumuna, yazılım sınırının [{2}, {3}] ötesine giderdi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="109" />
      <source>back off</source>
      <translation>anahtardan geri çekilme</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="72" />
      <source>backing off the switch</source>
      <translation>anahtardan geri çekiliyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="73" />
      <source>block delete changes which lines the program has: switch it before cycle start, not during a run</source>
      <translation>blok atlama programın hangi satırlara sahip olduğunu değiştirir: çevrim başlatmadan önce değiştirin, çalışırken değil</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="263" />
      <source>bus</source>
      <translation>veri yolu</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="324" />
      <source>cannot change the offsets of the coordinate system in use with cutter compensation on</source>
      <translation>kesici telafisi açıkken kullanılan koordinat sisteminin ofsetleri değiştirilemez</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="325" />
      <source>cannot move rotary axes with G76</source>
      <translation>G76 ile döner eksenler hareket ettirilemez</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="326" />
      <source>cannot probe ({0}) in {1}: program G94 first</source>
      <translation>{1} içinde problanamaz ({0}): önce G94 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="327" />
      <source>cannot probe ({0}) with cutter radius compensation on: program G40 first</source>
      <translation>kesici yarıçap telafisi açıkken problanamaz ({0}): önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="328" />
      <source>cannot probe ({0}) with zero feed rate: program an F word</source>
      <translation>sıfır ilerleme hızıyla problanamaz ({0}): bir F kelimesi programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="329" />
      <source>cannot put an {0} word in a canned cycle</source>
      <translation>sabit çevrime {0} kelimesi konamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="330" />
      <source>cannot read subroutine file {0}: {1}</source>
      <translation>{0} alt program dosyası okunamıyor: {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="331" />
      <source>cannot run a NURBS with cutter radius compensation on: program G40 first</source>
      <translation>kesici yarıçap telafisi açıkken NURBS çalıştırılamaz: önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="332" />
      <source>cannot run a curve ({0}) with cutter radius compensation on: program G40 first</source>
      <translation>kesici yarıçap telafisi açıkken eğri ({0}) çalıştırılamaz: önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="74" />
      <source>cannot save machine state: {0}</source>
      <translation>makine durumu kaydedilemiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="75" />
      <source>cannot save the G-code parameters: {0}</source>
      <translation>G kodu parametreleri kaydedilemiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="76" />
      <source>cannot save the part counter: {0}</source>
      <translation>parça sayacı kaydedilemiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="77" />
      <source>cannot save the tool in the spindle: {0}</source>
      <translation>iş milindeki takım kaydedilemiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="78" />
      <source>cannot save the tool table: {0}</source>
      <translation>takım tablosu kaydedilemiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="79" />
      <source>cannot save work offsets: {0}</source>
      <translation>iş ofsetleri kaydedilemiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="80" />
      <source>cannot start the bus: {0}</source>
      <translation>veri yolu başlatılamıyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="333" />
      <source>cannot tap (G33.1) with cutter radius compensation on: program G40 first</source>
      <translation>kesici yarıçap telafisi açıkken kılavuz çekilemez (G33.1): önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="334" />
      <source>cannot turn cutter compensation on with {0} while it is on ({1}): program G40 first</source>
      <translation>kesici telafisi açıkken ({1}) {0} ile yeniden açılamaz: önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="335" />
      <source>cannot use G33 with cutter radius compensation on: program G40 first</source>
      <translation>kesici yarıçap telafisi açıkken G33 kullanılamaz: önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="336" />
      <source>cannot use G53 with cutter compensation on: program G40 first</source>
      <translation>kesici telafisi açıkken G53 kullanılamaz: önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="337" />
      <source>cannot use axis values with G80</source>
      <translation>G80 ile eksen değerleri kullanılamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="338" />
      <source>cannot use canned cycles with cutter compensation on ({0})</source>
      <translation>kesici telafisi açıkken sabit çevrimler kullanılamaz ({0})</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="339" />
      <source>cannot use inverse time feed (G93) with canned cycles</source>
      <translation>sabit çevrimlerle ters zaman ilerlemesi (G93) kullanılamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="340" />
      <source>cannot use polar coordinates (@ ^) with X or Y words</source>
      <translation>kutupsal koordinatlar (@ ^) X ya da Y kelimeleriyle kullanılamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="341" />
      <source>cannot use the G76 threading cycle with cutter radius compensation on: program G40 first</source>
      <translation>kesici yarıçap telafisi açıkken G76 diş çevrimi kullanılamaz: önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="342" />
      <source>cannot use two G codes that both use axis values ({0} and a motion code)</source>
      <translation>ikisi de eksen değerlerini kullanan iki G kodu kullanılamaz ({0} ve bir hareket kodu)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="343" />
      <source>cannot wait for a digital input (M66) with cutter radius compensation on</source>
      <translation>kesici yarıçap telafisi açıkken dijital giriş beklenemez (M66)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="81" />
      <source>cannot write {0}: {1}</source>
      <translation>{0} yazılamıyor: {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="344" />
      <source>cannot {0} overrides with cutter radius compensation on ({1}): program G40 first</source>
      <translation>kesici yarıçap telafisi açıkken ({1}) ayar oranları şu yapılamaz: {0}; önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="345" />
      <source>cannot {0} with cutter compensation on ({1}): program G40 first</source>
      <translation>kesici telafisi açıkken ({1}) şu yapılamaz: {0}; önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="195" />
      <source>chain and door closed</source>
      <translation>devre ve kapı kapalı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="39" />
      <source>change the axis offsets (G52, G92)</source>
      <translation>eksen ofsetlerini değiştirmek (G52, G92)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="38" />
      <source>change the canned cycle retract mode</source>
      <translation>sabit çevrimin geri çekme kipini değiştirmek</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="40" />
      <source>change the coordinate system</source>
      <translation>koordinat sistemini değiştirmek</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="38" />
      <source>change the path control mode</source>
      <translation>yol kontrol kipini değiştirmek</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="37" />
      <source>change the plane</source>
      <translation>düzlemi değiştirmek</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="40" />
      <source>change the tool length offset</source>
      <translation>takım boyu ofsetini değiştirmek</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="40" />
      <source>change tools</source>
      <translation>takım değiştirmek</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="36" />
      <source>clockwise</source>
      <translation>saat yönünde</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="194" />
      <source>column {0}: {1}</source>
      <translation>sütun {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/spindle_view.py" line="42" />
      <source>commanded</source>
      <translation>istenen</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="88" />
      <source>completed</source>
      <translation>tamamlandı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="264" />
      <source>configuration</source>
      <translation>yapılandırma</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="103" />
      <source>connected</source>
      <translation>bağlı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="264" />
      <source>controller</source>
      <translation>denetleyici</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="268" />
      <source>coolant</source>
      <translation>soğutma sıvısı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="36" />
      <source>counterclockwise</source>
      <translation>saat yönünün tersine</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="346" />
      <source>cutter compensation in G18 with the XY plane rotated (G10 L2 R) is not supported: cancel the rotation (G10 L2 R0) or program the tool centre's path</source>
      <translation>XY düzlemi döndürülmüşken (G10 L2 R) G18'de kesici telafisi desteklenmiyor: döndürmeyi iptal edin (G10 L2 R0) ya da takım merkezinin yolunu programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="347" />
      <source>cutter compensation made an arc whose radius changes from {0} to {1} mm (an error of this control: please report the program)</source>
      <translation>kesici telafisi yarıçapı {0} mm'den {1} mm'ye değişen bir yay yaptı (bu kontrolün bir hatası: lütfen programı bildirin)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="348" />
      <source>cutter compensation works in the XY (G17) or XZ (G18) plane, not in {0}</source>
      <translation>kesici telafisi XY (G17) ya da XZ (G18) düzleminde çalışır, {0} içinde değil</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="56" />
      <source>cycles</source>
      <translation>çevrim</translation>
    </message>
    <message>
      <location filename="../../app/widgets/probing_panel.py" line="297" />
      <source>diameter</source>
      <translation>çap</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="82" />
      <source>direction must be +1 or -1, got {0}</source>
      <translation>yön +1 ya da -1 olmalı, {0} verildi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="36" />
      <source>disable</source>
      <translation>kapatmak</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="14" />
      <source>disabled</source>
      <translation>devre dışı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="77" />
      <source>disconnected</source>
      <translation>bağlı değil</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="268" />
      <source>door</source>
      <translation>kapı</translation>
    </message>
    <message>
      <location filename="../../app/widgets/status_header.py" line="196" />
      <source>door closed</source>
      <translation>kapı kapalı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="81" />
      <source>drive fault on axis {0} (slave {1}): error code {2}: quick stop of all axes</source>
      <translation>{0} ekseninde sürücü hatası (bağımlı {1}): hata kodu {2}: tüm eksenler hızlı durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="105" />
      <source>drive homing method {0}</source>
      <translation>sürücü referanslama yöntemi {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="275" />
      <source>drive {0}</source>
      <translation>sürücü {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="131" />
      <source>drive {0} (slave {1}) {2} bit {3}</source>
      <translation>{0} sürücüsü (bağımlı {1}) {2} bit {3}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="83" />
      <source>drives cannot be enabled: {0}</source>
      <translation>sürücüler etkinleştirilemiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="349" />
      <source>duplicate O-word label: o{0} {1} uses the label of the {2} at {3}</source>
      <translation>yinelenen O-kelimesi etiketi: o{0} {1}, {3} konumundaki {2} etiketini kullanıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="77" />
      <source>e-stop</source>
      <translation>acil stop</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="84" />
      <source>empty block</source>
      <translation>boş blok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="36" />
      <source>enable</source>
      <translation>açmak</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="14" />
      <source>enabled</source>
      <translation>etkin</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="14" />
      <source>enabling</source>
      <translation>etkinleştiriliyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="169" />
      <source>end point</source>
      <translation>bitiş noktası</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="16" />
      <source>error</source>
      <translation>hata</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="350" />
      <source>every NURBS control point needs a positive weight P</source>
      <translation>her NURBS kontrol noktası pozitif bir P ağırlığı ister</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="351" />
      <source>expression nested too deeply</source>
      <translation>ifade çok derin iç içe</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="15" />
      <source>fault</source>
      <translation>arıza</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="16" />
      <source>fault reset</source>
      <translation>arıza sıfırlama</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="48" />
      <source>feed hold</source>
      <translation>ilerleme durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="180" />
      <source>feed move with the spindle stopped: the M6 at line {0} stopped it and no M3/M4 started it again</source>
      <translation>iş mili dururken ilerleme hareketi: {0}. satırdaki M6 onu durdurdu ve hiçbir M3/M4 yeniden başlatmadı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="66" />
      <source>feed override must be 0-{0} %, got {1}</source>
      <translation>ilerleme oranı %0-{0} olmalı, {1} verildi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="68" />
      <source>feed override {0} % capped at {1} % here: the machine's speed, acceleration or jerk limit</source>
      <translation>ilerleme oranı %{0} burada %{1} ile sınırlandı: makinenin hız, ivme ya da sarsıntı sınırı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="87" />
      <source>feed override {0} % not applied here: the program turned it off (tapping, M49 or M50 P0) and runs its own feed</source>
      <translation>ilerleme oranı %{0} burada uygulanmıyor: program onu kapattı (kılavuz çekme, M49 ya da M50 P0) ve kendi ilerlemesini kullanıyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="352" />
      <source>feed rate is zero: program an F word before the first G01/G02/G03</source>
      <translation>ilerleme hızı sıfır: ilk G01/G02/G03'ten önce bir F kelimesi programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="88" />
      <source>flood coolant (M8)</source>
      <translation>bol soğutma sıvısı (M8)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="79" />
      <source>following error on axis {0}: {1} exceeds window {2} for more than {3} cycles: quick stop of all axes</source>
      <translation>{0} ekseninde takip hatası: {1}, {2} penceresini {3} çevrimden uzun aştı: tüm eksenler hızlı durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="353" />
      <source>g must be 2 or 3</source>
      <translation>g, 2 ya da 3 olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="89" />
      <source>gantry {0}: homed state cleared at connecting: only homing squares its two sides again, home it</source>
      <translation>gantri {0}: bağlanırken referans durumu silindi: iki tarafını yalnızca referanslama yeniden gönyeye getirir, referanslayın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="115" />
      <source>gantry {0}: its drives {1} and {2} are {3} out of square (window {4}) for more than {5} cycles: quick stop of all axes</source>
      <translation>gantri {0}: {1} ve {2} sürücüleri {5} çevrimden uzun süre {3} gönye dışı (pencere {4}): tüm eksenler hızlı durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="120" />
      <source>handwheel on axis {0}: its counter jumped by {1} counts in one cycle (a terminal restarted or a wire is loose): the jump moved nothing, the axis stopped; select the axis again to go on</source>
      <translation>{0} eksenindeki el çarkı: sayacı bir çevrimde {1} sayım sıçradı (bir terminal yeniden başladı ya da bir kablo gevşek): sıçrama hiçbir şeyi hareket ettirmedi, eksen durdu; devam etmek için ekseni yeniden seçin</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="122" />
      <source>handwheel on axis {0}: its encoder terminal stopped answering: the axis stopped; select the axis again once it answers</source>
      <translation>{0} eksenindeki el çarkı: enkoder terminali yanıt vermiyor: eksen durdu; yanıt verdiğinde ekseni yeniden seçin</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="77" />
      <source>hold</source>
      <translation>beklemede</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="77" />
      <source>homing</source>
      <translation>referanslanıyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="90" />
      <source>homing cannot be stopped mid-way: use E-stop</source>
      <translation>referanslama yarıda durdurulamaz: acil stopu kullanın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="88" />
      <source>homing of axis {0} failed ({1})</source>
      <translation>{0} ekseninin referanslanması başarısız ({1})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="108" />
      <source>homing of axis {0} failed at step '{1}': {2}; quick stop of all axes</source>
      <translation>{0} ekseninin referanslaması '{1}' adımında başarısız: {2}; tüm eksenler hızlı durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="91" />
      <source>homing refused: {0}</source>
      <translation>referanslama reddedildi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="113" />
      <source>homing {0}</source>
      <translation>referanslama {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="77" />
      <source>idle</source>
      <translation>boşta</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="92" />
      <source>increment must be one of {0}, got {1}</source>
      <translation>adım şunlardan biri olmalı: {0}; {1} verildi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="354" />
      <source>incremental motion with polar coordinates is indeterminate at the origin</source>
      <translation>kutupsal koordinatlarla artımsal hareket orijinde belirsizdir</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="109" />
      <source>index</source>
      <translation>indeks</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="25" />
      <source>info</source>
      <translation>bilgi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="267" />
      <source>input</source>
      <translation>giriş</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="93" />
      <source>input {0} is not in the program</source>
      <translation>{0} girişi programda yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="170" />
      <source>interrupted at line {0}: the control stopped (power loss or killed)</source>
      <translation>{0}. satırda kesildi: kontrol durdu (elektrik kesintisi veya sonlandırma)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="112" />
      <source>its drive has no touch probe (0x60B8, 0x60B9, 0x60BA) in its process data for the index</source>
      <translation>sürücüsünün proses verisinde indeks için dokunma probu (0x60B8, 0x60B9, 0x60BA) yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="94" />
      <source>jog released</source>
      <translation>elle hareket bırakıldı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="355" />
      <source>joined rows: {0} of {1}</source>
      <translation>birleştirilen satırlar: {0} / {1}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="109" />
      <source>latch</source>
      <translation>kenar yakalama</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="95" />
      <source>latching the switch edge</source>
      <translation>anahtar kenarı yakalanıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="155" />
      <source>line {0} comes after the probe at line {1}: what follows depends on what it read; run from line {1} (or before) to read it again</source>
      <translation>satır {0}, satır {1}'deki probdan sonra geliyor: devamı onun okuduğuna bağlı; yeniden okumak için satır {1}'den (veya öncesinden) çalıştırın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="96" />
      <source>line {0} comes after {1} at line {2}: what follows depends on what it read; run from line {3} (or before) to read it again</source>
      <translation>{0}. satır, {2}. satırdaki {1} komutundan sonra geliyor: devamı onun okuduğuna bağlı; yeniden okumak için {3}. satırdan (ya da öncesinden) çalıştırın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="74" />
      <source>line {0} needs T{1} in the spindle (T{2} is in it): put it in and set it on the Tools page, or run from the M6 line {3}</source>
      <translation>{0}. satır için iş milinde T{1} gerekli (şu an T{2} takılı): takın ve Takımlar sayfasında seçin ya da {3}. satırdaki M6 satırından çalıştırın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="29" />
      <source>line {0}, axis {1}: {2}</source>
      <translation>satır {0}, eksen {1}: {2}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="34" />
      <source>line {0}: {1}</source>
      <translation>satır {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="56" />
      <source>linear</source>
      <translation>doğrusal</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="98" />
      <source>lubricant level or pressure present</source>
      <translation>yağ seviyesi veya basıncı var</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="269" />
      <source>lubrication</source>
      <translation>yağlama</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="53" />
      <source>machine is {0}</source>
      <translation>makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="356" />
      <source>machine work offset {0} has {1} values for {2} axes</source>
      <translation>makine iş ofseti {0}, {2} eksen için {1} değer içeriyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="169" />
      <source>max</source>
      <translation>üst</translation>
    </message>
    <message>
      <location filename="../../app/widgets/tracking_view.py" line="104" />
      <source>max |e|</source>
      <translation>en büyük |e|</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="100" />
      <source>measuring on a tool setter needs X, Y and Z axes</source>
      <translation>takım ayarlayıcıda ölçüm X, Y ve Z eksenlerini ister</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="153" />
      <source>measuring tool T{0}</source>
      <translation>T{0} takımı ölçülüyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="169" />
      <source>min</source>
      <translation>alt</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="101" />
      <source>mist coolant (M7)</source>
      <translation>buhar soğutma (M7)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="357" />
      <source>mixed radius (R) and centre (I/J/K) format for arc</source>
      <translation>yay için yarıçap (R) ve merkez (I/J/K) biçimi karışık</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="358" />
      <source>more than {0} blocks run (an endless loop?)</source>
      <translation>{0} bloktan fazlası çalıştı (sonsuz döngü mü?)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="359" />
      <source>more than {0} roughing passes (the cycle does not progress)</source>
      <translation>{0} kaba pasodan fazla (çevrim ilerlemiyor)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="360" />
      <source>move index {0} outside 0..{1}</source>
      <translation>hareket sırası {0}, 0..{1} dışında</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="102" />
      <source>moving off the switch</source>
      <translation>anahtardan çıkıyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="361" />
      <source>negative dwell time P{0}</source>
      <translation>negatif bekleme süresi P{0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="362" />
      <source>negative feed F{0}</source>
      <translation>negatif ilerleme F{0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="363" />
      <source>negative spindle speed S{0}</source>
      <translation>negatif iş mili hızı S{0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="364" />
      <source>negative surface speed S{0}</source>
      <translation>negatif yüzey hızı S{0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="365" />
      <source>nested comment: '(' inside a comment</source>
      <translation>iç içe açıklama: açıklama içinde '('</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="103" />
      <source>no</source>
      <translation>hayır</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="103" />
      <source>no active alarm with id {0}</source>
      <translation>{0} kimlikli etkin alarm yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="111" />
      <source>no index pulse within the search travel</source>
      <translation>arama mesafesi içinde indeks darbesi yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="366" />
      <source>no motion at or after line {0}</source>
      <translation>{0}. satırda ya da sonrasında hareket yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="104" />
      <source>no probe in the spindle: put it in and set it (In the spindle) first</source>
      <translation>iş milinde prob yok: önce takın ve ayarlayın (İş milinde)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="105" />
      <source>no probe is named: set [probe] tool to the probe's number in the tool table (only the probe may make probing moves)</source>
      <translation>hiçbir prob tanımlı değil: [probe] tool anahtarına probun takım tablosundaki numarasını yazın (prob hareketlerini yalnızca prob yapabilir)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="57" />
      <source>no program loaded</source>
      <translation>yüklü program yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="162" />
      <source>no program stopped part-way</source>
      <translation>yarıda durmuş bir program yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="107" />
      <source>no tool is in the spindle, not the probe T{0}: put the probe in and say so (In the spindle, or M61 Q{1})</source>
      <translation>iş milinde takım yok, prob T{0} de yok: probu takın ve bildirin (İş milinde ya da M61 Q{1})</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="43" />
      <source>no tool length offset</source>
      <translation>takım boy ofseti yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="108" />
      <source>no tool setter on this machine ([probe] drive, setter_x_mm, setter_y_mm and setter_z_mm in the machine configuration)</source>
      <translation>bu makinede takım ayarlayıcı yok (makine yapılandırmasında [probe] drive, setter_x_mm, setter_y_mm ve setter_z_mm)</translation>
    </message>
    <message>
      <location filename="../../app/format.py" line="43" />
      <source>none</source>
      <translation>yok</translation>
    </message>
    <message>
      <location filename="../../app/widgets/spindle_view.py" line="116" />
      <source>not at speed</source>
      <translation>hızında değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="109" />
      <source>not connected</source>
      <translation>bağlı değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="110" />
      <source>not while the machine is {0}</source>
      <translation>makine {0} durumundayken olmaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="111" />
      <source>nothing is moving</source>
      <translation>hareket eden bir şey yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="54" />
      <source>nothing to hold: machine is {0}</source>
      <translation>durdurulacak bir şey yok: makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="113" />
      <source>nothing to resume: machine is {0}</source>
      <translation>devam edilecek bir şey yok: makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="114" />
      <source>nothing to stop: machine is {0}</source>
      <translation>durdurulacak bir şey yok: makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="367" />
      <source>o&lt;{0}&gt; call: no o&lt;{1}&gt; sub in this program and no {2}.ngc in the subroutine folders ({3})</source>
      <translation>o&lt;{0}&gt; call: bu programda o&lt;{1}&gt; sub yok ve alt program klasörlerinde {2}.ngc yok ({3})</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="174" />
      <source>off</source>
      <translation>kapalı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="109" />
      <source>off switch</source>
      <translation>anahtardan çıkma</translation>
    </message>
    <message>
      <location filename="../../app/widgets/signals_view.py" line="47" />
      <source>on</source>
      <translation>açık</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="115" />
      <source>on while the spindle turns</source>
      <translation>iş mili dönerken açık</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="116" />
      <source>only a simulated machine's handwheel can be turned</source>
      <translation>yalnızca simüle edilen bir makinenin el çarkı çevrilebilir</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="117" />
      <source>only a simulated machine's inputs can be set</source>
      <translation>yalnızca benzetimli bir makinenin girişleri ayarlanabilir</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="118" />
      <source>only a simulated spindle drive can be loaded</source>
      <translation>yalnızca benzetimli bir iş mili sürücüsü yüklenebilir</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="264" />
      <source>operator</source>
      <translation>operatör</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="109" />
      <source>optional</source>
      <translation>isteğe bağlı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="44" />
      <source>optional stop (M01, line {0}): press cycle start</source>
      <translation>isteğe bağlı duruş (M01, satır {0}): çevrim başlata basın</translation>
    </message>
    <message>
      <location filename="../../app/widgets/signals_view.py" line="18" />
      <source>output</source>
      <translation>çıkış</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="119" />
      <source>output {0} could not be switched off: {1}</source>
      <translation>{0} çıkışı kapatılamadı: {1}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="267" />
      <source>outputs</source>
      <translation>çıkışlar</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="368" />
      <source>o{0} call with {1} arguments (at most 30: #1-#30)</source>
      <translation>{1} argümanla o{0} call (en çok 30: #1-#30)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="369" />
      <source>o{0} call: no o{1} sub in this program</source>
      <translation>o{0} call: bu programda o{1} sub yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="370" />
      <source>o{0} call: the o{1} sub at line {2} is not defined here: the program did not run through it (a sub inside an if is defined only when that branch runs) and no other is ahead of the call</source>
      <translation>o{0} call: {2}. satırdaki o{1} sub burada tanımlı değil: program onun içinden geçmedi (bir if içindeki sub yalnızca o dal çalışınca tanımlanır) ve çağrının ilerisinde başkası yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="371" />
      <source>o{0} call: the subroutine number {1} is not a whole number from 0 to 1e9</source>
      <translation>o{0} call: {1} alt program numarası 0 ile 1e9 arasında bir tam sayı değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="372" />
      <source>o{0} repeat [{1}]: the count is out of range (|count| &lt; 1e9)</source>
      <translation>o{0} repeat [{1}]: sayı aralığın dışında (|sayı| &lt; 1e9)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="373" />
      <source>o{0} repeat needs one count in brackets</source>
      <translation>o{0} repeat köşeli parantez içinde bir sayı ister</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="374" />
      <source>o{0} sub is defined twice: already at line {1}</source>
      <translation>o{0} sub iki kez tanımlanmış: {1}. satırda zaten var</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="375" />
      <source>o{0} sub met a second time: a sub is defined once, as the program runs through it or a call finds it ahead (not inside a loop, nor after a call to it)</source>
      <translation>o{0} sub ikinci kez görüldü: bir sub bir kez tanımlanır, program içinden geçerken ya da bir çağrı onu ileride bulurken (bir döngü içinde değil, ona yapılan bir çağrıdan sonra da değil)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="376" />
      <source>o{0} {1} is not supported</source>
      <translation>o{0} {1} desteklenmiyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="377" />
      <source>o{0} {1} needs one condition in brackets</source>
      <translation>o{0} {1} köşeli parantez içinde bir koşul ister</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="169" />
      <source>path</source>
      <translation>yol</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="263" />
      <source>planner</source>
      <translation>planlayıcı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="120" />
      <source>planner: {0}</source>
      <translation>planlayıcı: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="378" />
      <source>polar coordinates (@ ^) can only be used for motion</source>
      <translation>kutupsal koordinatlar (@ ^) yalnızca hareket için kullanılabilir</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="379" />
      <source>polar coordinates (@ ^) need X and Y axes</source>
      <translation>kutupsal koordinatlar (@ ^) X ve Y eksenlerini ister</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="380" />
      <source>polar coordinates (@ ^) only in the XY plane (G17)</source>
      <translation>kutupsal koordinatlar (@ ^) yalnızca XY düzleminde (G17)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="165" />
      <source>power loss or killed</source>
      <translation>elektrik kesintisi veya sonlandırma</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="265" />
      <source>probe</source>
      <translation>prob</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="381" />
      <source>probe result {0} has positions for {1} axes, the machine has {2}</source>
      <translation>{0} prob sonucunda {1} eksen için konum var, makinede {2} eksen var</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="186" />
      <source>probe touched during positioning</source>
      <translation>konumlanma sırasında prob temas etti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="188" />
      <source>probed (machine): {0} (only reported)</source>
      <translation>problandı (makine): {0} (yalnızca bildirildi)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="187" />
      <source>probed (machine): {0}, written to {1}</source>
      <translation>problandı (makine): {0}, {1} sistemine yazıldı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="121" />
      <source>probing a part needs X, Y and Z axes</source>
      <translation>bir parçayı problamak X, Y ve Z eksenlerini ister</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="187" />
      <source>probing {0}</source>
      <translation>prob ölçümü: {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="183" />
      <source>probing {0}: {1}</source>
      <translation>prob ölçümü: {0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="266" />
      <source>program</source>
      <translation>program</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="51" />
      <source>program end</source>
      <translation>program sonu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="43" />
      <source>program paused (M00, line {0}): press cycle start</source>
      <translation>program duraklatıldı (M00, satır {0}): çevrim başlata basın</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="26" />
      <source>quick stop</source>
      <translation>hızlı durdurma</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="87" />
      <source>quick stop of all axes: {0}</source>
      <translation>tüm eksenler hızlı durduruldu: {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/profile_plots.py" line="13" />
      <source>rapid</source>
      <translation>hızlı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="122" />
      <source>rapid override must be 0-{0} %, got {1}</source>
      <translation>hızlı hareket oranı %0-{0} olmalı, {1} verildi</translation>
    </message>
    <message>
      <location filename="../../app/widgets/spindle_view.py" line="43" />
      <source>read</source>
      <translation>okunan</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="109" />
      <source>required before a program may start</source>
      <translation>program başlamadan önce gerekli</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="164" />
      <source>reset</source>
      <translation>sıfırlama</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="123" />
      <source>reset not possible: machine is {0}</source>
      <translation>sıfırlama yapılamaz: makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/pages/axes.py" line="56" />
      <source>rotary</source>
      <translation>döner</translation>
    </message>
    <message>
      <location filename="../../app/pages/manual.py" line="66" />
      <source>rpm</source>
      <translation>dev/dk</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="163" />
      <source>run from line {0}</source>
      <translation>{0}. satırdan çalıştırma</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="77" />
      <source>running</source>
      <translation>çalışıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="109" />
      <source>search</source>
      <translation>arama</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="124" />
      <source>searching the index pulse</source>
      <translation>indeks darbesini arıyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="125" />
      <source>searching the switch</source>
      <translation>anahtar aranıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="37" />
      <source>set a digital output</source>
      <translation>dijital çıkış ayarlamak</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="37" />
      <source>set an analog output</source>
      <translation>analog çıkış ayarlamak</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="107" />
      <source>set current position as zero (no reference switches: after a power loss the part zero must be touched off again)</source>
      <translation>mevcut konum sıfır olarak ayarlanır (referans anahtarı yok: elektrik kesintisinden sonra parça sıfırı yeniden dokunarak alınmalı)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="90" />
      <source>set-point buffer underrun after {0} set-points: holding the last position</source>
      <translation>{0} hedef noktadan sonra hedef tamponu boşaldı: son konum tutuluyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="126" />
      <source>single block takes effect at the next stop (feed hold, block end, M00)</source>
      <translation>tek blok bir sonraki duruşta etkili olur (ilerleme durdurma, blok sonu, M00)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="47" />
      <source>single block: end of line {0}</source>
      <translation>tek blok: {0}. satırın sonu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="31" />
      <source>soft limit: {0}</source>
      <translation>yazılım sınırı: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="128" />
      <source>speed must be 0-{0} rpm</source>
      <translation>hız 0-{0} dev/dak olmalı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="266" />
      <source>spindle</source>
      <translation>iş mili</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="129" />
      <source>spindle cannot start: machine is {0}</source>
      <translation>iş mili başlatılamıyor: makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="382" />
      <source>spindle not turning in G33.1 (rigid tapping needs M3 or M4 and S)</source>
      <translation>G33.1'de iş mili dönmüyor (rijit kılavuz çekme M3 ya da M4 ve S ister)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="383" />
      <source>spindle not turning in G86</source>
      <translation>G86'da iş mili dönmüyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="384" />
      <source>spindle not turning in {0} (M3 or M4 first)</source>
      <translation>{0} içinde iş mili dönmüyor (önce M3 ya da M4)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="385" />
      <source>spindle not turning in {0} (tapping needs M0{1})</source>
      <translation>{0} içinde iş mili dönmüyor (kılavuz çekme M0{1} ister)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="130" />
      <source>spindle output failed: {0}</source>
      <translation>iş mili çıkışı başarısız: {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="67" />
      <source>spindle override must be 50-150 %, got {0}</source>
      <translation>iş mili oranı %50-150 olmalı, {0} verildi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="131" />
      <source>spindle override must be {0}-{1} %, got {2}</source>
      <translation>iş mili oranı %{0}-{1} olmalı, {2} verildi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="69" />
      <source>spindle override {0} % capped at {1} %: the spindle's maximum is {2} rpm</source>
      <translation>iş mili oranı %{0}, %{1} ile sınırlandı: iş milinin en yüksek hızı {2} dev/dk</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="133" />
      <source>spindle override {0} % not applied now: the program turned it off (tapping, M49 or M51 P0); it applies once the program turns it on</source>
      <translation>iş mili oranı %{0} şimdi uygulanmıyor: program onu kapattı (kılavuz çekme, M49 ya da M51 P0); program açınca uygulanır</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="134" />
      <source>spindle override {0} %: the feed waits until the spindle turns at {1} rpm</source>
      <translation>iş mili oranı %{0}: ilerleme, iş mili {1} dev/dak dönene kadar bekler</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="386" />
      <source>spindle turning {0} in {1}</source>
      <translation>{1} içinde iş mili {0} dönüyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="109" />
      <source>square</source>
      <translation>gönye</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="135" />
      <source>squaring the gantry</source>
      <translation>gantri gönyeye getiriliyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="117" />
      <source>squaring the gantry would move this side further than its homing travel</source>
      <translation>gantriyi gönyeye getirmek bu tarafı referanslama yolundan daha uzağa götürürdü</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="55" />
      <source>start jitter (µs)</source>
      <translation>başlangıç sapması (µs)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="387" />
      <source>start_position has {0} values for {1} axes</source>
      <translation>start_position, {1} eksen için {0} değer içeriyor</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="13" />
      <source>starting</source>
      <translation>başlıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="265" />
      <source>state folder</source>
      <translation>durum klasörü</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="25" />
      <source>stop</source>
      <translation>durdurma</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="13" />
      <source>stopped</source>
      <translation>durdu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="50" />
      <source>stopped by the operator</source>
      <translation>operatör tarafından durduruldu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="49" />
      <source>stopping</source>
      <translation>duruyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="39" />
      <source>store the G28/G30 position</source>
      <translation>G28/G30 konumunu kaydetmek</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="388" />
      <source>subprogram calls nested deeper than {0} (endless recursion?)</source>
      <translation>alt program çağrıları {0} düzeyden derin (sonsuz özyineleme mi?)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="389" />
      <source>subroutine calls nested deeper than {0} (endless recursion?)</source>
      <translation>alt yordam çağrıları {0} düzeyden derin (sonsuz özyineleme mi?)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="137" />
      <source>the 1 ms loop refused the handwheel (the axis is moving, or set-points are queued)</source>
      <translation>1 ms döngüsü el çarkını reddetti (eksen hareket ediyor ya da sırada hedef noktalar var)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="138" />
      <source>the E-stop chain (safety relay) is closed; open: E-stop, no reset until closed</source>
      <translation>acil stop zinciri (güvenlik rölesi) kapalı; açılırsa: acil stop, kapanana kadar sıfırlama yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="139" />
      <source>the E-stop chain is open: release the E-stop buttons and close the safety circuit first</source>
      <translation>acil stop devresi açık: önce acil stop düğmelerini bırakın ve güvenlik devresini kapatın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="140" />
      <source>the Z surface</source>
      <translation>Z yüzeyi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="141" />
      <source>the angle of a face</source>
      <translation>bir yüzün açısı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="184" />
      <source>the bore measures {0} mm across, not {1} mm within {2} mm: nothing written</source>
      <translation>delik çapı {0} mm ölçüldü, {2} mm içinde {1} mm değil: hiçbir şey yazılmadı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="185" />
      <source>the boss measures {0} mm across, not {1} mm within {2} mm: nothing written</source>
      <translation>pim çapı {0} mm ölçüldü, {2} mm içinde {1} mm değil: hiçbir şey yazılmadı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="142" />
      <source>the bus is not connected</source>
      <translation>veri yolu bağlı değil</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="92" />
      <source>the control did not shut down cleanly (power loss or killed; position last saved {0}): {1}</source>
      <translation>kontrol düzgün kapanmadı (elektrik kesintisi ya da zorla sonlandırma; konum en son {0} tarihinde kaydedildi): {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="390" />
      <source>the cutter compensation entry move ({0} mm in the plane) is not longer than the tool radius ({1} mm)</source>
      <translation>kesici telafisi giriş hareketi (düzlemde {0} mm) takım yarıçapından ({1} mm) uzun değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="143" />
      <source>the depth below the start must be above 0 mm</source>
      <translation>başlangıcın altındaki derinlik 0 mm'den büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="144" />
      <source>the diameter must be above 0 mm</source>
      <translation>çap 0 mm'den büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="145" />
      <source>the diameter's tolerance must be above 0 mm</source>
      <translation>çap toleransı 0 mm'den büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="146" />
      <source>the direction is +X, -X, +Y or -Y</source>
      <translation>yön +X, -X, +Y ya da -Y olur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="147" />
      <source>the distance along the faces must be above 0 mm</source>
      <translation>yüzler boyunca mesafe 0 mm'den büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="148" />
      <source>the door is open: close it first</source>
      <translation>kapı açık: önce kapatın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="149" />
      <source>the door is open: jogging needs it closed on this machine ([interlocks] door_open_jog_mm_s)</source>
      <translation>kapı açık: bu makinede elle hareket için kapalı olmalı ([interlocks] door_open_jog_mm_s)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="150" />
      <source>the door is open: the handwheel needs it closed on this machine</source>
      <translation>kapı açık: bu makinede el çarkı için kapının kapalı olması gerekir</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="151" />
      <source>the door was opened while homing</source>
      <translation>referanslama sırasında kapı açıldı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="152" />
      <source>the door was opened: the spindle stopped</source>
      <translation>kapı açıldı: iş mili durdu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="104" />
      <source>the drives cannot be re-enabled: axis {0} is on its negative limit switch: override limits to jog it off the switch</source>
      <translation>sürücüler yeniden etkinleştirilemiyor: {0} ekseni negatif sınır anahtarında: anahtardan çıkarmak için sınırları geçersiz kılın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="102" />
      <source>the drives cannot be re-enabled: axis {0} is on its positive limit switch: override limits to jog it off the switch</source>
      <translation>sürücüler yeniden etkinleştirilemiyor: {0} ekseni pozitif sınır anahtarında: anahtardan çıkarmak için sınırları geçersiz kılın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="153" />
      <source>the drives cannot be re-enabled: {0}</source>
      <translation>sürücüler yeniden etkinleştirilemiyor: {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="94" />
      <source>the drives have absolute encoders: homed flags kept</source>
      <translation>sürücülerde mutlak enkoder var: referans bilgisi korundu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="149" />
      <source>the fast probe down to the setter</source>
      <translation>takım ölçere hızlı prob inişi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="154" />
      <source>the guard door is closed; open: a program holds and the spindle stops</source>
      <translation>koruma kapısı kapalı; açılırsa: program bekler ve iş mili durur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="155" />
      <source>the handwheel is still moving axis {0}: let it stand, then try again</source>
      <translation>el çarkı {0} eksenini hâlâ hareket ettiriyor: durmasını bekleyin, sonra yeniden deneyin</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="156" />
      <source>the handwheel's axis selector stands on this axis</source>
      <translation>el çarkının eksen seçicisi bu eksende</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="157" />
      <source>the handwheel's step selector stands on x10</source>
      <translation>el çarkının adım seçicisi x10 konumunda</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="158" />
      <source>the handwheel's step selector stands on x100</source>
      <translation>el çarkının adım seçicisi x100 konumunda</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="159" />
      <source>the home switch</source>
      <translation>referans anahtarı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="160" />
      <source>the lube pump, on while the drives are on</source>
      <translation>yağlama pompası, sürücüler açıkken açık</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="63" />
      <source>the machine configuration changed since it was loaded</source>
      <translation>makine ayarları, program yüklendiğinden beri değişti</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="161" />
      <source>the machine has no Z axis</source>
      <translation>makinede Z ekseni yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="162" />
      <source>the machine is still stopping: wait for standstill</source>
      <translation>makine hâlâ duruyor: tam duruşu bekleyin</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="163" />
      <source>the machine is {0}</source>
      <translation>makine {0} durumunda</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="61" />
      <source>the machine moved since it was loaded</source>
      <translation>makine, program yüklendiğinden beri hareket etti</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="164" />
      <source>the machine's Cycle start button</source>
      <translation>makinenin Çevrim başlat düğmesi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="165" />
      <source>the machine's Feed hold button</source>
      <translation>makinenin İlerlemeyi durdur düğmesi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="166" />
      <source>the machine's Stop button</source>
      <translation>makinenin Dur düğmesi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="152" />
      <source>the move back up</source>
      <translation>yukarı geri dönüş</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="391" />
      <source>the move just after turning cutter compensation off (G40) must be a straight line, not an arc</source>
      <translation>kesici telafisi kapatıldıktan (G40) hemen sonraki hareket yay değil, doğru olmalı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="148" />
      <source>the move over the tool setter</source>
      <translation>takım ölçerin üzerine gidiş</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="167" />
      <source>the move to the home position was refused: {0}</source>
      <translation>referans konumuna hareket reddedildi: {0}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="150" />
      <source>the move up from the first contact</source>
      <translation>ilk temastan yukarı çıkış</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="147" />
      <source>the move up to the clearance height</source>
      <translation>emniyet yüksekliğine çıkış</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="168" />
      <source>the negative limit switch</source>
      <translation>negatif sınır anahtarı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="169" />
      <source>the pendant's selector chooses the handwheel's axis and step on this machine</source>
      <translation>bu makinede el çarkının eksenini ve adımını el kumandasının seçicisi belirler</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="170" />
      <source>the positive limit switch</source>
      <translation>pozitif sınır anahtarı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="392" />
      <source>the program aborts here (ABORT comment): {0}</source>
      <translation>program burada durduruluyor (ABORT açıklaması): {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="393" />
      <source>the program ends with the NURBS begun at line {0} not ended: program G05.3 to run it</source>
      <translation>program, {0}. satırda başlayan NURBS bitirilmeden sona eriyor: çalıştırmak için G05.3 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="394" />
      <source>the program ends with this NURBS (G05.2) not ended: program G05.3 to run it</source>
      <translation>program bu NURBS (G05.2) bitirilmeden sona eriyor: çalıştırmak için G05.3 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="161" />
      <source>the program stopped at line {0}: resume there or start it again from the beginning (choose one)</source>
      <translation>program {0}. satırda durdu: oradan devam edin ya da baştan başlatın (birini seçin)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="172" />
      <source>the program {0} is being planned for single block (wait until it is ready)</source>
      <translation>{0} programı tek blok için planlanıyor (hazır olana kadar bekleyin)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="59" />
      <source>the program {0} is still being checked (wait until it is loaded)</source>
      <translation>{0} programı hâlâ denetleniyor (yüklenene kadar bekleyin)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="395" />
      <source>the radius of the cutter compensation entry arc is not greater than the tool radius ({0} mm)</source>
      <translation>kesici telafisi giriş yayının yarıçapı takım yarıçapından ({0} mm) büyük değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="396" />
      <source>the routine after a tool change ({0}) is not an O-word call</source>
      <translation>takım değişiminden sonraki yordam ({0}) bir O-kelimesi çağrısı değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="397" />
      <source>the routine after a tool change ({0}): {1}</source>
      <translation>takım değişiminden sonraki yordam ({0}): {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="174" />
      <source>the set-points ran out after {0} (the control's process fell behind): the axes braked to rest along the path within their limits</source>
      <translation>referans noktaları {0} sonrasında tükendi (kontrolün işlemi geride kaldı): eksenler yol boyunca sınırları içinde frenlenerek durdu</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="151" />
      <source>the slow probe down to the setter</source>
      <translation>takım ölçere yavaş prob inişi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="175" />
      <source>the slow probe feed F{0} must be below the fast one F{1} mm/min: the edge is read at the slow one</source>
      <translation>yavaş prob ilerlemesi F{0}, hızlı olan F{1} mm/dk değerinin altında olmalı: kenar yavaş olanla okunur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="176" />
      <source>the spindle did not reach its speed within {0} s: its drive reads {1} rpm</source>
      <translation>iş mili {0} s içinde hızına ulaşmadı: sürücüsü {1} dev/dak okuyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="177" />
      <source>the spindle did not report at speed (spindle_at_speed) within {0} s</source>
      <translation>iş mili {0} s içinde hızına ulaştığını bildirmedi (spindle_at_speed)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="178" />
      <source>the spindle drive reports the commanded speed</source>
      <translation>iş mili sürücüsü istenen hıza ulaştığını bildirir</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="179" />
      <source>the spindle lost speed: {0} rpm read against {1} commanded for {2} s (a band of {3} %)</source>
      <translation>iş mili hız kaybetti: {2} s boyunca istenen {1} dev/dak yerine {0} dev/dak okundu (%{3} bant)</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="280" />
      <source>the spindle starts at {0:.0f} rpm {1} before it goes down</source>
      <translation>iş mili inmeden önce {0:.0f} dev/dk {1} döner</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="279" />
      <source>the spindle stays off</source>
      <translation>iş mili kapalı kalır</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="180" />
      <source>the spindle's drive refused to turn (faulted, stopping, or the drives are off)</source>
      <translation>iş mili sürücüsü dönmeyi reddetti (arızalı, duruyor ya da sürücüler kapalı)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="181" />
      <source>the spindle's speed output failed: {0}</source>
      <translation>iş milinin hız çıkışı başarısız: {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="182" />
      <source>the surface height must be a number</source>
      <translation>yüzey yüksekliği bir sayı olmalı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="110" />
      <source>the switch did not change within the search travel</source>
      <translation>anahtar arama mesafesi içinde değişmedi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="192" />
      <source>the target of {0} part(s) is reached: reset the part counter (or raise the target) to run again</source>
      <translation>{0} parçalık hedefe ulaşıldı: yeniden çalıştırmak için parça sayacını sıfırlayın (ya da hedefi yükseltin)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="171" />
      <source>the tool length offset in force changed since it was loaded</source>
      <translation>yüklendiğinden beri geçerli takım boy ofseti değişti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="70" />
      <source>the tool table cannot change while the machine is {0}: a program reads the offsets when it is checked</source>
      <translation>makine {0} durumundayken takım tablosu değiştirilemez: program, ofsetleri denetlenirken okur</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="64" />
      <source>the tool table changed since it was loaded</source>
      <translation>takım tablosu, program yüklendiğinden beri değişti</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="185" />
      <source>the work light</source>
      <translation>çalışma lambası</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="62" />
      <source>the work offsets changed since it was loaded</source>
      <translation>iş ofsetleri, program yüklendiğinden beri değişti</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="186" />
      <source>this CPU does not keep stores in order: the 1 ms loop runs as a thread of the panel, not in its own process (less punctual under GUI load)</source>
      <translation>bu işlemci yazmaları sırayla tutmuyor: 1 ms döngüsü kendi sürecinde değil, panelin bir iş parçacığı olarak çalışıyor (arayüz yükü altında daha az dakik)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="187" />
      <source>this machine has no handwheel ([handwheel] terminal)</source>
      <translation>bu makinenin el çarkı yok ([handwheel] terminal)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="188" />
      <source>this machine has no probe input ([probe] drive in the machine configuration)</source>
      <translation>bu makinede prob girişi yok (makine yapılandırmasında [probe] drive)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="189" />
      <source>this machine has no reference switches ([homing] method = "set_here"): where its axes stand after the cut is not known, so machine zero set now would not be the old one; the part zero must be touched off again</source>
      <translation>bu makinede referans anahtarı yok ([homing] method = "set_here"): kesintiden sonra eksenlerin nerede durduğu bilinmiyor, şimdi ayarlanan makine sıfırı eskisi olmaz; parça sıfırı yeniden dokunarak alınmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="190" />
      <source>this machine's spindle has no drive of its own ([spindle] drive): no speed is read to lose</source>
      <translation>bu makinenin iş milinin kendi sürücüsü yok ([spindle] drive): kaybedilecek okunan bir hız yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="111" />
      <source>timeout</source>
      <translation>zaman aşımı</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="106" />
      <source>to the home switches, in the configured sequence</source>
      <translation>referans anahtarlarına, yapılandırılan sırayla</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="398" />
      <source>tool T{0} is not in the tool table (add it on the Tools page)</source>
      <translation>T{0} takımı takım tablosunda yok (Takımlar sayfasında ekleyin)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="45" />
      <source>tool change (M06, line {0}): insert tool {1} and press cycle start</source>
      <translation>takım değişimi (M06, satır {0}): {1} takımını takın ve çevrim başlata basın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="399" />
      <source>tool number H{0} must be a whole number &gt;= 0</source>
      <translation>takım numarası H{0}, &gt;= 0 bir tam sayı olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="400" />
      <source>tool number Q{0} must be a whole number &gt;= 0</source>
      <translation>takım numarası Q{0}, &gt;= 0 bir tam sayı olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="401" />
      <source>tool number T{0} must be a whole number &gt;= 0</source>
      <translation>takım numarası T{0}, &gt;= 0 bir tam sayı olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="402" />
      <source>tool radius ({0} mm) not less than the arc radius ({1} mm) with cutter compensation</source>
      <translation>kesici telafisiyle takım yarıçapı ({0} mm) yay yarıçapından ({1} mm) küçük değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="403" />
      <source>tool radius ({0} mm) not less than the arc radius with cutter compensation</source>
      <translation>kesici telafisiyle takım yarıçapı ({0} mm) yay yarıçapından küçük değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="404" />
      <source>tool radius not less than the arc radius with cutter compensation</source>
      <translation>kesici telafisiyle takım yarıçapı yay yarıçapından küçük değil</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="282" />
      <source>tool {0}</source>
      <translation>takım {0}</translation>
    </message>
    <message>
      <location filename="../../app/widgets/dro.py" line="41" />
      <source>tool {0}length {1} mm</source>
      <translation>takım {0}boy {1} mm</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="405" />
      <source>tool_offset {0}: G43, G43.1, G43.2 or G49 and {1} values</source>
      <translation>tool_offset {0}: G43, G43.1, G43.2 ya da G49 ve {1} değer</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="265" />
      <source>tools</source>
      <translation>takımlar</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="176" />
      <source>touch off {0}: not a number</source>
      <translation>{0} sıfırlama: sayı değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="406" />
      <source>two {0} words in one block</source>
      <translation>bir blokta iki {0} kelimesi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="407" />
      <source>unclosed comment: '(' without ')'</source>
      <translation>kapanmamış açıklama: ')' olmadan '('</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="95" />
      <source>unknown</source>
      <translation>bilinmiyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="408" />
      <source>unknown G code G{0}</source>
      <translation>bilinmeyen G kodu G{0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="409" />
      <source>unknown G code {0}</source>
      <translation>bilinmeyen G kodu {0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="410" />
      <source>unknown M code M{0}</source>
      <translation>bilinmeyen M kodu M{0}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="192" />
      <source>unknown work offset {0} (G54-G59.3)</source>
      <translation>bilinmeyen iş ofseti {0} (G54-G59.3)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="41" />
      <source>use {0}</source>
      <translation>{0} kullanmak</translation>
    </message>
    <message>
      <location filename="../../app/widgets/handwheel_box.py" line="68" />
      <source>waiting for the drives</source>
      <translation>sürücüler bekleniyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="25" />
      <source>warning</source>
      <translation>uyarı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="411" />
      <source>with cutter compensation this arc would turn a whole circle more than programmed: the arc is too short for the tool's radius</source>
      <translation>kesici telafisiyle bu yay programlanandan bir tam tur fazla dönerdi: yay takımın yarıçapı için fazla kısa</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="412" />
      <source>word {0} is not supported</source>
      <translation>{0} kelimesi desteklenmiyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="263" />
      <source>worker</source>
      <translation>çevrim işçisi</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="82" />
      <source>working counter {0} instead of {1} for more than {2} cycles: quick stop of all axes{3}</source>
      <translation>çalışma sayacı {2} çevrimden uzun süre {1} yerine {0}: tüm eksenler hızlı durduruldu{3}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="413" />
      <source>x too large in straight dive</source>
      <translation>düz dalışta x fazla büyük</translation>
    </message>
    <message>
      <location filename="../../app/pages/machine_zero.py" line="103" />
      <source>yes</source>
      <translation>evet</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="217" />
      <source>{0} (checking…)</source>
      <translation>{0} (denetleniyor…)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="77" />
      <source>{0} (compensation {1:+.4f})</source>
      <translation>{0} (kompanzasyon {1:+.4f})</translation>
    </message>
    <message>
      <location filename="../../app/widgets/bus_view.py" line="75" />
      <source>{0} (gantry {1}, skew {2:+.4f})</source>
      <translation>{0} (gantri {1}, kayma {2:+.4f})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="135" />
      <source>{0} (line {1}): contact at {2} (machine)</source>
      <translation>{0} (satır {1}): temas {2} konumunda (makine)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="136" />
      <source>{0} (line {1}): contact lost at {2} (machine)</source>
      <translation>{0} (satır {1}): temas {2} konumunda kesildi (makine)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="137" />
      <source>{0} (line {1}): no contact</source>
      <translation>{0} (satır {1}): temas yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="139" />
      <source>{0} (line {1}): the probe already touches where the move starts</source>
      <translation>{0} (satır {1}): prob, hareketin başladığı yerde zaten temas ediyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="138" />
      <source>{0} (line {1}): the probe move ended without contact</source>
      <translation>{0} (satır {1}): prob hareketi temas olmadan bitti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="140" />
      <source>{0} (line {1}): with the result, {2}</source>
      <translation>{0} (satır {1}): sonuçla birlikte, {2}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="131" />
      <source>{0} (slave {1}) channel {2}</source>
      <translation>{0} (bağımlı {1}) kanal {2}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="129" />
      <source>{0} ({1})</source>
      <translation>{0} ({1})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="142" />
      <source>{0} ({1}): contact at {2} (machine)</source>
      <translation>{0} ({1}): temas {2} konumunda (makine)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="143" />
      <source>{0} ({1}): no contact</source>
      <translation>{0} ({1}): temas yok</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="145" />
      <source>{0} ({1}): the probe already touches where the move starts</source>
      <translation>{0} ({1}): prob, hareketin başladığı yerde zaten temas ediyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="144" />
      <source>{0} ({1}): the probe move ended without contact</source>
      <translation>{0} ({1}): prob hareketi temas olmadan bitti</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="146" />
      <source>{0} ({1}): with the result, {2}</source>
      <translation>{0} ({1}): sonuçla birlikte, {2}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="414" />
      <source>{0} L{1}: lathe tool orientations are not supported on this machine (L0 or L9: the centre of the tool)</source>
      <translation>{0} L{1}: torna takımı yönelimleri bu makinede desteklenmiyor (L0 ya da L9: takımın merkezi)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="415" />
      <source>{0} Q{1}: no o{2} sub in this program (the profile)</source>
      <translation>{0} Q{1}: bu programda o{2} sub yok (profil)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="416" />
      <source>{0} Q{1}: the profile's subroutine number is a whole number</source>
      <translation>{0} Q{1}: profilin alt program numarası bir tam sayıdır</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="141" />
      <source>{0} XY rotation (degrees, as G10 L2 R)</source>
      <translation>{0} XY dönüşü (derece, G10 L2 R gibi)</translation>
    </message>
    <message>
      <location filename="../../app/widgets/production_view.py" line="120" />
      <source>{0} and {1}</source>
      <translation>{0} ve {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="417" />
      <source>{0} and {1} are in the same modal group (one per block)</source>
      <translation>{0} ve {1} aynı kip grubunda (blok başına bir tane)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="126" />
      <source>{0} at the switch</source>
      <translation>{0} anahtarda</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="125" />
      <source>{0} backing off the switch</source>
      <translation>{0} anahtardan geri çekiliyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="418" />
      <source>{0} before the NURBS begun at line {1} is ended: program G05.3 to run it first</source>
      <translation>{1}. satırda başlayan NURBS bitmeden {0}: önce onu çalıştırmak için G05.3 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="419" />
      <source>{0} beside G05.3: between G05.2 and G05.3 only G05.2 blocks</source>
      <translation>G05.3 yanında {0}: G05.2 ile G05.3 arasında yalnızca G05.2 blokları olur</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="420" />
      <source>{0} blocks run without a move (an endless loop?)</source>
      <translation>hareketsiz {0} blok çalıştı (sonsuz döngü mü?)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="421" />
      <source>{0} can only be used in the XZ plane (G18)</source>
      <translation>{0} yalnızca XZ düzleminde (G18) kullanılabilir</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="422" />
      <source>{0} canned cycle is not possible on a machine without {1} axis</source>
      <translation>{0} sabit çevrimi {1} ekseni olmayan bir makinede yapılamaz</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="423" />
      <source>{0} cannot be used with cutter compensation enabled: program G40 first</source>
      <translation>{0}, kesici telafisi açıkken kullanılamaz: önce G40 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="424" />
      <source>{0} characters of code in one block (comments aside): more than {1}, the most a block may have (LinuxCNC reads 255 a line)</source>
      <translation>bir blokta {0} karakter kod (yorumlar hariç): bir bloğun olabileceği en çok {1} karakterden fazla (LinuxCNC bir satırda 255 okur)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="425" />
      <source>{0} cuts in X and Z: this machine has no {1} axis</source>
      <translation>{0}, X ve Z'de keser: bu makinede {1} ekseni yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="426" />
      <source>{0} does not define o{1} sub</source>
      <translation>{0}, o{1} sub tanımlamıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="28" />
      <source>{0} error(s) in the program; first: {1}</source>
      <translation>programda {0} hata; ilki: {1}</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="189" />
      <source>{0} error(s); first at line {1}: {2}</source>
      <translation>{0} hata; ilki {1}. satırda: {2}</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="232" />
      <source>{0} has unsaved changes.</source>
      <translation>{0} dosyasında kaydedilmemiş değişiklikler var.</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="307" />
      <source>{0} has {1} error(s), the first at line {2}: {3}. Save it anyway?</source>
      <translation>{0} içinde {1} hata var, ilki {2}. satırda: {3}. Yine de kaydedilsin mi?</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="427" />
      <source>{0} in a concave corner cannot be reached by the tool without gouging (the corner's sides are shorter than the tool needs)</source>
      <translation>içbükey köşedeki {0} hareketine takım oyuk açmadan ulaşamaz (köşenin kenarları takımın gerektirdiğinden kısa)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="428" />
      <source>{0} in inverse time feed mode (G93): program G94 or G95 for curves</source>
      <translation>ters zaman ilerleme kipinde (G93) {0}: eğriler için G94 ya da G95 programlayın</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="169" />
      <source>{0} is in the spindle, {1} is selected. Whose length is measured?</source>
      <translation>İş milinde {0} var, {1} seçili. Hangisinin boyu ölçülüyor?</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="429" />
      <source>{0} is not a motion this interpreter runs</source>
      <translation>{0}, bu yorumlayıcının çalıştırdığı bir hareket değil</translation>
    </message>
    <message>
      <location filename="../../app/pages/tools.py" line="209" />
      <source>{0} is not a tool table in the program folders</source>
      <translation>{0} program klasörlerinde bir takım tablosu değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="193" />
      <source>{0} is not a wired input (inputs: {1})</source>
      <translation>{0} bağlı bir giriş değil (girişler: {1})</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="430" />
      <source>{0} is not supported ({1})</source>
      <translation>{0} desteklenmiyor ({1})</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="126" />
      <source>{0} latching the switch edge</source>
      <translation>{0} anahtar kenarı yakalanıyor</translation>
    </message>
    <message>
      <location filename="../../app/pages/program.py" line="149" />
      <source>{0} lines: shown read-only (edit programs of over {1} lines in CAM or on a PC)</source>
      <translation>{0} satır: yalnızca okunur gösteriliyor ({1} satırdan uzun programları CAM'de ya da bir bilgisayarda düzenleyin)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="132" />
      <source>{0} lost ({1} reads false)</source>
      <translation>{0} kayboldu ({1} yanlış okuyor)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="133" />
      <source>{0} lost ({1} reads false): the motion stops</source>
      <translation>{0} kayboldu ({1} yanlış okuyor): hareket duruyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="89" />
      <source>{0} lost: not answering process data; trying to recover it when it comes back</source>
      <translation>{0} kayboldu: süreç verisine yanıt vermiyor; geri geldiğinde kurtarılmaya çalışılacak</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="125" />
      <source>{0} moving off the switch</source>
      <translation>{0} anahtardan çıkıyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="431" />
      <source>{0} needs D to be a tool number (a whole number &gt;= 0), got D{1}</source>
      <translation>{0}, D'nin bir takım numarası olmasını ister (&gt;= 0 bir tam sayı), D{1} verildi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="432" />
      <source>{0} needs X or Y (all axes missing with a motion code)</source>
      <translation>{0}, X ya da Y ister (hareket koduyla birlikte tüm eksenler eksik)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="433" />
      <source>{0} needs a D word (the tool diameter)</source>
      <translation>{0} bir D kelimesi ister (takım çapı)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="434" />
      <source>{0} needs a K word (the thread pitch, length per turn)</source>
      <translation>{0} bir K kelimesi ister (diş hatvesi, tur başına boy)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="435" />
      <source>{0} needs a P word (the dwell at the bottom, s) the first time</source>
      <translation>{0} ilk seferde bir P kelimesi ister (tabanda bekleme, s)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="436" />
      <source>{0} needs a Q word (the peck depth) the first time</source>
      <translation>{0} ilk seferde bir Q kelimesi ister (gagalama derinliği)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="437" />
      <source>{0} needs a {1} word (the bottom of the hole) the first time in {2}</source>
      <translation>{0}, {2} içinde ilk seferde bir {1} kelimesi ister (deliğin tabanı)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="438" />
      <source>{0} needs an R word (the retract plane) the first time</source>
      <translation>{0} ilk seferde bir R kelimesi ister (geri çekme düzlemi)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="439" />
      <source>{0} needs an axis word (all axes missing with G52 or G92)</source>
      <translation>{0} bir eksen kelimesi ister (G52 ya da G92 ile hiçbir eksen yok)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="194" />
      <source>{0} needs {1} values</source>
      <translation>{0}, {1} değer ister</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="191" />
      <source>{0} part(s) made: the target of {1} is reached</source>
      <translation>{0} parça yapıldı: {1} hedefine ulaşıldı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="440" />
      <source>{0} requires a Q word (the number of the subroutine with the profile)</source>
      <translation>{0} bir Q kelimesi gerektirir (profili içeren alt programın numarası)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="196" />
      <source>{0} rotation: a number of degrees within -360 .. 360</source>
      <translation>{0} döndürme: -360 .. 360 arasında bir derece değeri</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="197" />
      <source>{0} rotation: not a number</source>
      <translation>{0} döndürme: sayı değil</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="126" />
      <source>{0} searching the index pulse</source>
      <translation>{0} indeks darbesini arıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="125" />
      <source>{0} searching the switch</source>
      <translation>{0} anahtar aranıyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="127" />
      <source>{0} squaring the gantry</source>
      <translation>{0} gantri gönyeye getiriliyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="441" />
      <source>{0} value {1} out of range (|value| &lt; {2})</source>
      <translation>{0} değeri {1} aralık dışında (|değer| &lt; {2})</translation>
    </message>
    <message>
      <location filename="../../app/main_window.py" line="196" />
      <source>{0} was running at line {1} when the control stopped (power loss or killed): home the axes, open it and run from line {1}</source>
      <translation>Kontrol durduğunda {0} {1}. satırda çalışıyordu (elektrik kesintisi veya sonlandırma): eksenleri referanslayın, programı açın ve {1}. satırdan çalıştırın</translation>
    </message>
    <message>
      <location filename="../../app/pages/auto.py" line="459" />
      <source>{0} was saved with changes since it was loaded: the machine runs the program as loaded.</source>
      <translation>{0} yüklendikten sonra değişikliklerle kaydedildi: makine programı yüklendiği haliyle çalıştırır.</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="442" />
      <source>{0} with the lathe tool {1} (orientation Q{2}): lathe tool orientations are not supported on this machine</source>
      <translation>{1} torna takımıyla {0} (yönelim Q{2}): torna takımı yönelimleri bu makinede desteklenmiyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="443" />
      <source>{0} with the spindle at S0: the feed, the pitch times the speed, would be 0</source>
      <translation>iş mili S0'dayken {0}: ilerleme, yani hatve çarpı hız, 0 olurdu</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="444" />
      <source>{0} word given for arc in the {1} plane ({2})</source>
      <translation>{1} düzlemindeki yay ({2}) için {0} kelimesi verildi</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="445" />
      <source>{0} word with no {1} to use it</source>
      <translation>{0} kelimesini kullanacak {1} yok</translation>
    </message>
    <message>
      <location filename="../../app/pages/part_zero.py" line="147" />
      <source>{0} {1} (machine coordinate of part zero)</source>
      <translation>{0} {1} (parça sıfırının makine koordinatı)</translation>
    </message>
    <message>
      <location filename="../../app/pages/alarms.py" line="109" />
      <source>{0} {1} ({2}, {3}): {4}</source>
      <translation>{0} {1} ({2}, {3}): {4}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="173" />
      <source>{0} {1} zero would be at machine {2} with the tool length offset in force, outside the travel {3} .. {4} {5}</source>
      <translation>{0} {1} sıfırı, geçerli takım boy ofsetiyle makinede {2} konumunda olurdu, {3} .. {4} {5} hareket aralığının dışında</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="175" />
      <source>{0} {1} zero would be at machine {2}, outside the travel {3} .. {4} {5}</source>
      <translation>{0} {1} sıfırı makinede {2} konumunda olurdu, {3} .. {4} {5} hareket aralığının dışında</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="131" />
      <source>{0}, normally closed</source>
      <translation>{0}, normalde kapalı</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="129" />
      <source>{0}, {1}</source>
      <translation>{0}, {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="446" />
      <source>{0}: I (the depth of cut) must be greater than zero</source>
      <translation>{0}: I (kesme derinliği) sıfırdan büyük olmalı</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="447" />
      <source>{0}: Q{1} over a depth of {2} makes more than {3} pecks</source>
      <translation>{0}: {2} derinlik boyunca Q{1}, {3} gagalamadan fazlasını yapar</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="448" />
      <source>{0}: a curve moves in X and Y only, not {1}</source>
      <translation>{0}: bir eğri yalnızca X ve Y'de hareket eder, {1} içinde değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="449" />
      <source>{0}: a pipe is read once: what it gave is not UTF-8</source>
      <translation>{0}: bir boru bir kez okunur: verdiği UTF-8 değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="450" />
      <source>{0}: binary data (a NUL byte), not {1}</source>
      <translation>{0}: ikili veri (bir NUL baytı), {1} değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="451" />
      <source>{0}: cannot read: {1}</source>
      <translation>{0}: okunamıyor: {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="198" />
      <source>{0}: cannot record the run: {1}</source>
      <translation>{0}: çalışma kaydedilemiyor: {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="452" />
      <source>{0}: curves only in the XY plane (G17)</source>
      <translation>{0}: eğriler yalnızca XY düzleminde (G17)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="453" />
      <source>{0}: is a folder, not {1}</source>
      <translation>{0}: bir klasör, {1} değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="454" />
      <source>{0}: more than {1} MB, the most {2} may have{3}</source>
      <translation>{0}: {1} MB'tan büyük, {2} için en büyük boyut{3}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="455" />
      <source>{0}: more than {1} profile blocks read (an endless loop?)</source>
      <translation>{0}: {1} profil bloğundan fazlası okundu (sonsuz döngü mü?)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="456" />
      <source>{0}: negative or zero Q (peck depth)</source>
      <translation>{0}: negatif ya da sıfır Q (gagalama derinliği)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="457" />
      <source>{0}: not UTF-8, and a pipe cannot be read again as Latin-1</source>
      <translation>{0}: UTF-8 değil ve bir boru Latin-1 olarak yeniden okunamaz</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="177" />
      <source>{0}: not a number</source>
      <translation>{0}: sayı değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="200" />
      <source>{0}: not a number (offsets are finite numbers)</source>
      <translation>{0}: sayı değil (ofsetler sonlu sayılardır)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="458" />
      <source>{0}: nothing came for {1} s (a pipe with no writer?)</source>
      <translation>{0}: {1} s boyunca hiçbir şey gelmedi (yazanı olmayan bir boru mu?)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="459" />
      <source>{0}: o{1} {2} ({3}) is not supported: a profile's calls are written out</source>
      <translation>{0}: o{1} {2} ({3}) desteklenmiyor: bir profilin çağrıları açık yazılır</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="201" />
      <source>{0}: planner: {1}</source>
      <translation>{0}: planlayıcı: {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="460" />
      <source>{0}: start point too close to probe point (the move has no length)</source>
      <translation>{0}: başlangıç noktası prob noktasına çok yakın (hareketin boyu yok)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="461" />
      <source>{0}: tables or arrays nested too deeply to read (a damaged file?)</source>
      <translation>{0}: tablolar ya da diziler okunamayacak kadar derin iç içe (bozuk bir dosya mı?)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="462" />
      <source>{0}: the profile cannot be offset or cut (a segment of no length, or the cycle's start on the profile)</source>
      <translation>{0}: profil ötelenemiyor ya da kesilemiyor (boyu olmayan bir parça ya da çevrimin başlangıcı profilin üzerinde)</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="202" />
      <source>{0}: the program cannot be read again with the result</source>
      <translation>{0}: program sonuçla birlikte yeniden okunamıyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="203" />
      <source>{0}: the program read again does not go on from where the machine stands</source>
      <translation>{0}: yeniden okunan program makinenin durduğu yerden devam etmiyor</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="204" />
      <source>{0}: the program read again does not have it</source>
      <translation>{0}: yeniden okunan programda o yok</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="205" />
      <source>{0}: with the result the program reads: {1}</source>
      <translation>{0}: sonuçla birlikte program şöyle okunuyor: {1}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="32" />
      <source>{0}: with the result, line {1} reads: {2}</source>
      <translation>{0}: sonuçla birlikte {1}. satır şöyle okunuyor: {2}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="33" />
      <source>{0}: with the result, line {1}: {2}</source>
      <translation>{0}: sonuçla birlikte {1}. satır: {2}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="208" />
      <source>{0}: with the result, {1}</source>
      <translation>{0}: sonuçla birlikte, {1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="209" />
      <source>{0}: with the result, {1} line {2} reads: {3}</source>
      <translation>{0}: sonuçla birlikte {1} dosyasının {2}. satırı şöyle okunuyor: {3}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="129" />
      <source>{0}: {1}</source>
      <translation>{0}: {1}</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="60" />
      <source>{0}: {1} is being checked again; it starts when ready</source>
      <translation>{0}: {1} yeniden denetleniyor; hazır olunca başlayacak</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="463" />
      <source>{0}:{1}: binary data (a NUL byte), not {2}</source>
      <translation>{0}:{1}: ikili veri (bir NUL baytı), {2} değil</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="464" />
      <source>{0}:{1}: not UTF-8 text ({2} is)</source>
      <translation>{0}:{1}: UTF-8 metin değil ({2} öyledir)</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="27" />
      <source>{0}:{1}:{2}: error: {3}</source>
      <translation>{0}:{1}:{2}: hata: {3}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="210" />
      <source>{0}; it starts when ready</source>
      <translation>{0}; hazır olunca başlayacak</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="211" />
      <source>{0}; the machine runs on without its OPC UA server</source>
      <translation>{0}; makine OPC UA sunucusu olmadan çalışmaya devam ediyor</translation>
    </message>
    <message>
      <location filename="../../app/controller_text.py" line="46" />
      <source>{0}; {1} is then measured on the tool setter</source>
      <translation>{0}; {1} ardından takım ayarlayıcıda ölçülür</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="465" />
      <source>{0}both A and C on a corner{1}</source>
      <translation>{0}bir köşede hem A hem C{1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="466" />
      <source>{0}both R and I or K for an arc{1}</source>
      <translation>{0}bir yay için hem R hem I ya da K{1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="467" />
      <source>{0}cannot use {1} and {2} in the same block{3}</source>
      <translation>{0}{1} ve {2} aynı blokta kullanılamaz{3}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="468" />
      <source>{0}cannot use {1} in incremental mode (G91){2}</source>
      <translation>{0}{1} artımsal kipte (G91) kullanılamaz{2}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="469" />
      <source>{0}either I or K must be present for an arc{1}</source>
      <translation>{0}bir yay için I ya da K bulunmalı{1}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="470" />
      <source>{0}radius R{1} too small for the arc{2}</source>
      <translation>{0}R{1} yarıçapı yay için fazla küçük{2}</translation>
    </message>
    <message>
      <location filename="../../app/message_text.py" line="471" />
      <source>{0}{1} value {2} out of range (|value| &lt; 1e9){3}</source>
      <translation>{0}{1} değeri {2} aralığın dışında (|değer| &lt; 1e9){3}</translation>
    </message>
  </context>
</TS>
